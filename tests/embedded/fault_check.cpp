// Proves that the harness reports a fault instead of hanging or passing: an
// unaligned word store, which the RP2040's Cortex-M0+ always faults on and
// qemu's Cortex-M3 faults on only because startup.cpp sets CCR.UNALIGN_TRP.
// The m0_fault_check test passes when the fault report appears.
#include <cstdint>
#include <cstdio>

namespace {
alignas(4) char g_buffer[8];
// volatile: hides the misalignment from the compiler, which would otherwise
// split the store into byte stores (as it must for a known-unaligned address).
volatile std::uintptr_t g_address = reinterpret_cast<std::uintptr_t>(&g_buffer[1]);
}  // namespace

int main() {
  std::puts("storing a word at an unaligned address");
  *reinterpret_cast<volatile std::uint32_t*>(g_address) = 1;
  std::puts("no fault: the target does not trap unaligned accesses");
  return 0;
}
