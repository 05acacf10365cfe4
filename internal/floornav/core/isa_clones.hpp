#pragma once
/// @file
/// FLOORNAV_ISA_CLONES, for the library's own hot loops (public because modules at every layer
/// use it).
//
// A function marked with it is compiled twice, for x86-64-v3 (AVX2, BMI: VEX's
// three-operand forms, a rounding instruction for floor) and for the baseline x86-64, the loader
// taking the one the CPU runs (GCC's target_clones, an ELF ifunc). Both do the same IEEE
// operations in the same order, none fused (the project builds with -ffp-contract=off), so the
// results are the same to the bit on every machine; only the speed differs.
// `flatten` inlines what the function calls into each clone: a lambda left out of line would be
// compiled once, for the baseline. Off with the CMake option FLOORNAV_ISA_CLONES=OFF (the
// sanitizer build: it tests the baseline's code, the others the clone the machine runs).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__ELF__) && \
    !defined(FLOORNAV_NO_ISA_CLONES)
#define FLOORNAV_ISA_CLONES __attribute__((flatten, target_clones("arch=x86-64-v3", "default")))
#else
#define FLOORNAV_ISA_CLONES
#endif
