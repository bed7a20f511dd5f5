// The source of ontogen_test_pch (tests/CMakeLists.txt), an executable that does nothing:
// it only precompiles the headers the test executables share, compiled as they are.
int main() { return 0; }
