// The unit that builds the test executables' precompiled header (tests/CMakeLists.txt); it has
// no code of its own.
