// Fuzzes the input stage of `splinecal fit` (files and flags, read and checked up to the
// heavy work); the input format is in command_inputs.h.
#include "command_inputs.h"

SPLINECAL_COMMAND_INPUTS_FUZZER("fit")
