// The one line of an InputError, for tests of bad input.
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "core/errors.h"

namespace vkp::test {

/// The message of the InputError that f throws ("" and a test failure if it throws none).
template <class F>
std::string inputErrorOf(F&& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "no InputError";
    return {};
}

}  // namespace vkp::test
