// YUXI_HD marks a function that runs on both sides: compiled by nvcc it is
// __host__ __device__, by g++ or clang it is an ordinary function. The contact laws, the vector
// arithmetic they use and the contact geometry are written once with it (docs/ARCHITECTURE.md,
// "The seam for a second backend"), and a test compiles their headers with nvcc.
#pragma once

#if defined(__CUDACC__)
#define YUXI_HD __host__ __device__
#else
#define YUXI_HD
#endif
