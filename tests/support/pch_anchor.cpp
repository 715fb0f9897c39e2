// The one source of freeform_test_pch (tests/CMakeLists.txt): the target exists to build the
// precompiled header that every test executable reuses; this file adds nothing to it.
