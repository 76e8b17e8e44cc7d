// Fuzzes the input stage of `splinecal correct` (files and flags, read and checked up to the
// correction); the input format is in command_inputs.h.
#include "command_inputs.h"

SPLINECAL_COMMAND_INPUTS_FUZZER("correct")
