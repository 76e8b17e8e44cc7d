// Long work without the GIL, stoppable with Ctrl-C. Python runs its signal handlers only on the
// main thread, between bytecodes, i.e. never during a C++ solve; so the solve polls instead:
// SolverOptions::stop (estimation/solve_rounds.h) takes the GIL once per solver iteration and
// calls PyErr_CheckSignals(). When a handler raised (KeyboardInterrupt for Ctrl-C), the solve
// aborts and the pending Python exception is raised in place of the library's result or error.
//
// A test hook makes the interrupt deterministic (python/tests/test_interrupt.py; a timer on two
// loaded cores may fire before the solve starts or after it ends): with
// SPLINECAL_TEST_SIGINT_AT_POLL=n in the environment, the n-th poll of a solve raises SIGINT in
// the solving thread itself, as a Ctrl-C arriving during that iteration would, and then polls.
#ifndef SPLINECAL_PYTHON_INTERRUPTIBLE_H_
#define SPLINECAL_PYTHON_INTERRUPTIBLE_H_

#include <pybind11/pybind11.h>

#include <csignal>
#include <cstdlib>
#include <memory>
#include <utility>

#include "splinecal/estimation/solve_rounds.h"

namespace splinecal {
namespace python {

// Runs work() with the GIL released and `solver` (the options work() solves with) stoppable.
template <typename Work>
auto RunInterruptible(SolverOptions* solver, Work&& work) -> decltype(work()) {
  namespace py = pybind11;
  auto interrupted = std::make_shared<bool>(false);
  const char* hook = std::getenv("SPLINECAL_TEST_SIGINT_AT_POLL");
  const long sigint_at_poll = hook != nullptr ? std::atol(hook) : 0;
  auto polls = std::make_shared<long>(0);
  solver->stop = [interrupted, sigint_at_poll, polls] {
    py::gil_scoped_acquire gil;
    if (++*polls == sigint_at_poll) std::raise(SIGINT);
    if (PyErr_CheckSignals() != 0) *interrupted = true;  // the exception stays pending
    return *interrupted;
  };
  try {
    auto result = [&] {
      py::gil_scoped_release release;
      return std::forward<Work>(work)();
    }();
    if (*interrupted) throw py::error_already_set();
    return result;
  } catch (const py::error_already_set&) {
    throw;
  } catch (...) {
    // An aborted solve fails in the library's words; the user pressed Ctrl-C.
    if (*interrupted) throw py::error_already_set();
    throw;
  }
}

// Runs work() with the GIL released (work that polls nothing: a Ctrl-C waits for its end).
template <typename Work>
auto RunWithoutGil(Work&& work) -> decltype(work()) {
  pybind11::gil_scoped_release release;
  return std::forward<Work>(work)();
}

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_INTERRUPTIBLE_H_
