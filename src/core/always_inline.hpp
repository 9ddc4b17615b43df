// Marks a function the compiler must inline where the optimiser's size heuristics would not:
// contact laws called once per touching pair from the templated pair loop, where a call costs
// as much as the arithmetic (GCC and Clang attribute; other compilers treat it as plain inline).
#pragma once

#if defined(__GNUC__) || defined(__clang__)
#define YUXI_ALWAYS_INLINE [[gnu::always_inline]] inline
#else
#define YUXI_ALWAYS_INLINE inline
#endif
