#pragma once
// The io test helpers and the names every io test uses, brought into the global namespace. Only for the
// tests/io files: other test areas include io_test_util.hpp, which declares nothing globally.
#include "io_test_util.hpp"

// Names every io test uses.
using namespace shoremesh;
using namespace shoremesh::io;
using shoremesh::io::test::expect_input_error;
using shoremesh::io::test::samples;
using ::testing::HasSubstr;
