// Compiled only to build tests/pch/test_pch.hpp into a precompiled header.
