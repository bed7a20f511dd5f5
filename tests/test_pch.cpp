// The source of ontogen_test_pch (tests/CMakeLists.txt), which only precompiles the
// headers the test executables share.
