#pragma once
/// Below this many items the mesher's OpenMP regions run on the calling thread
/// (`#pragma omp parallel ... if (count >= kMinParallelItems)`): waking a team costs 5–50 µs,
/// far more under OMP_WAIT_POLICY=passive, while 2048 items of the cheapest per-bubble loops
/// take ~0.1 ms. Every region computes the same result for any team size (contiguous blocks
/// concatenated in order, no floating reductions across threads), so this changes times only.
namespace ablmg::mesher {
inline constexpr int kMinParallelItems = 2048;
}  // namespace ablmg::mesher
