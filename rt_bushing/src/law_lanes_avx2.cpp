/* law_lanes_avx2.cpp -- the law sweep's kernels (law_lanes_kernel.h) for
 * AVX2: 4 doubles per vector. Compiled for that instruction set whatever
 * the build's -march; law_lanes.cpp calls it only where the CPU has it.
 */
#include "law_lanes.h"

#if RTB_LAW_LANES
/* No fused multiply-add whatever the build flags say (AVX-512 brings FMA
 * with it): the kernels give the same bits as every other build. */
#pragma GCC optimize("fp-contract=off")
#pragma GCC target("avx2")
#define LANES_W 4
#define LANES_SWEEP rtb_law_sweep_w4
#define LANES_KERNELS rtb_law_kernels_w4
#include "law_lanes_kernel.h"
#endif
