// Tests that need an OpenCL device: whether this machine has a usable one,
// and what to do without one. The README installs pocl, so a missing device
// fails such a test; POLYVOL_TEST_ALLOW_NO_DEVICE=1 makes it skip instead
// (the sanitizer builds, whose runtime cannot see into the driver).
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "polyvol/device.hpp"

namespace polyvol::test {

inline bool usable_opencl_device() {
    for (const DeviceInfo& d : list_devices().devices)
        if (d.usable) return true;
    return false;
}

inline bool no_device_allowed() {
    const char* allow = std::getenv("POLYVOL_TEST_ALLOW_NO_DEVICE");
    return allow && std::string(allow) == "1";
}

}  // namespace polyvol::test

// At the top of a test body: skip or fail unless a usable device exists.
#define POLYVOL_REQUIRE_OPENCL_DEVICE()                                                                     \
    do {                                                                                                  \
        if (!::polyvol::test::usable_opencl_device()) {                                                   \
            if (::polyvol::test::no_device_allowed()) GTEST_SKIP() << "no usable OpenCL device";          \
            FAIL() << "no usable OpenCL device (install pocl-opencl-icd): " << ::polyvol::list_devices().note; \
        }                                                                                                 \
    } while (0)
