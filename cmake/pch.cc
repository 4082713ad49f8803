// Compiled only to build the precompiled headers (cmake/PrecompiledHeaders.cmake).
