// Startup code for the qemu test images: vector table, reset handler, the
// command line from the host, and a fault handler that ends the run.
//
// The reset vector points here, not at newlib's rdimon-crt0 (_start, linked
// but dropped by --gc-sections): that crt0 takes its stack from the
// semihosting HEAPINFO call, which qemu answers for M-profile boards with
// addresses derived from a RAM size the MPS2 memory map does not have.
#include <sys/stat.h>

#include <cerrno>
#include <csignal>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <new>

extern "C" {
// Linker script symbols (mps2_an385.ld).
extern std::uint32_t __bss_start__[];
extern std::uint32_t __bss_end__[];
extern std::uint32_t __stack_top[];

void initialise_monitor_handles();  // librdimon: opens stdin/stdout/stderr on the host
void __libc_init_array();           // newlib: runs .preinit_array/.init_array (constructors)
// gtest_main.cc's main, under another C++ name: ISO C++ forbids calling main.
int rotord_test_main(int argc, char** argv) asm("main");
void _exit(int status);  // librdimon: semihosting SYS_EXIT with the status

// Semihosting has no directory operations and librdimon no mkdir; only
// gtest's --gtest_output=xml:DIR/ would create a directory.
int mkdir(const char* /*path*/, mode_t /*mode*/) {
  errno = ENOSYS;
  return -1;
}

[[noreturn]] void rotord_reset_handler();
[[noreturn]] void rotord_fault_handler();
}

namespace {

// ARM semihosting operation numbers (ARM DUI 0471, "Semihosting operations").
constexpr int kSysWrite0 = 0x04;
constexpr int kSysGetCmdline = 0x15;

// On ARMv6-M the semihosting trap is BKPT 0xAB: r0 = operation, r1 = argument.
int semihost(int operation, void* argument) {
  register int r0 asm("r0") = operation;
  register void* r1 asm("r1") = argument;
  asm volatile("bkpt 0xab" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void write0(const char* text) {
  semihost(kSysWrite0, const_cast<char*>(text));
}

// qemu-run.sh passes the test binary's arguments (e.g. --gtest_filter=...) as
// the semihosting command line; split on spaces, as the runner joins with them.
constexpr std::size_t kMaxArgs = 16;
char g_cmdline[512];
char* g_argv[kMaxArgs + 1];

int read_command_line() {
  struct {
    char* buffer;
    int length;
  } block{g_cmdline, static_cast<int>(sizeof g_cmdline) - 1};
  if (semihost(kSysGetCmdline, &block) != 0) return 0;
  g_cmdline[block.length] = '\0';
  int argc = 0;
  char* p = g_cmdline;
  while (*p != '\0' && argc < static_cast<int>(kMaxArgs)) {
    while (*p == ' ') *p++ = '\0';
    if (*p == '\0') break;
    g_argv[argc++] = p;
    while (*p != '\0' && *p != ' ') ++p;
  }
  g_argv[argc] = nullptr;
  return argc;
}

// Without exceptions, a failed allocation or std::terminate ends in abort(),
// which newlib turns into a bare exit status 1. Say why first.
void on_out_of_memory() {
  write0("\n*** operator new: out of memory ***\n");
  std::abort();
}

void on_abort(int /*signal*/) {
  write0("\n*** abort() ***\n");
}

}  // namespace

[[noreturn]] void rotord_reset_handler() {
  // The RP2040's Cortex-M0+ faults on every unaligned load or store; qemu's
  // Cortex-M3 would perform them unless CCR.UNALIGN_TRP asks it to trap. With
  // it set, a misaligned cast in the core fails here as it would on the Pico.
  constexpr std::uintptr_t kScbCcr = 0xE000ED14;
  constexpr std::uint32_t kUnalignTrp = 1u << 3;
  *reinterpret_cast<volatile std::uint32_t*>(kScbCcr) |= kUnalignTrp;
  // qemu loads .data from the ELF, so only .bss needs clearing; a flash-based
  // image would also copy .data here.
  std::memset(__bss_start__, 0,
              static_cast<std::size_t>(reinterpret_cast<char*>(__bss_end__) -
                                       reinterpret_cast<char*>(__bss_start__)));
  initialise_monitor_handles();
  std::set_new_handler(on_out_of_memory);
  std::signal(SIGABRT, on_abort);
  __libc_init_array();
  const int argc = read_command_line();
  std::exit(rotord_test_main(argc, g_argv));
}

// Any fault (HardFault is the only fault exception on ARMv6-M: unaligned
// access, undefined instruction, bad address...) ends the run with a message
// and a failing status instead of hanging until the ctest timeout.
extern "C" [[noreturn]] void rotord_report_fault(const std::uint32_t* frame) {
  std::uint32_t ipsr;
  asm volatile("mrs %0, ipsr" : "=r"(ipsr));
  char text[] = "\n*** exception 0x.. at pc 0x........ ***\n";
  constexpr char kHex[] = "0123456789abcdef";
  text[17] = kHex[(ipsr >> 4) & 0xF];
  text[18] = kHex[ipsr & 0xF];
  // The hardware stacked r0-r3, r12, lr, pc, xpsr: the faulting pc is word 6.
  for (int i = 0; i < 8; ++i) text[28 + i] = kHex[(frame[6] >> (28 - 4 * i)) & 0xF];
  write0(text);
  _exit(70);
  for (;;) {
  }
}

// Naked, so that the main stack pointer still points at the stacked frame when
// it is read. The tests never switch to the process stack.
__attribute__((naked)) void rotord_fault_handler() {
  asm volatile(
      "mrs r0, msp\n"
      "bl rotord_report_fault\n");
}

namespace {
using Handler = void (*)();
}

// The 16 ARMv6-M system vectors; the MPS2 peripherals' interrupts stay disabled.
__attribute__((section(".vectors"), used)) const Handler g_vectors[16] = {
    reinterpret_cast<Handler>(__stack_top),
    rotord_reset_handler,
    rotord_fault_handler,  // NMI
    rotord_fault_handler,  // HardFault
    rotord_fault_handler,  // MemManage (ARMv7-M only; qemu's MPS2 CPU is a Cortex-M3)
    rotord_fault_handler,  // BusFault (idem)
    rotord_fault_handler,  // UsageFault (idem)
    nullptr,
    nullptr,
    nullptr,
    nullptr,
    rotord_fault_handler,  // SVCall
    rotord_fault_handler,  // DebugMonitor
    nullptr,
    rotord_fault_handler,  // PendSV
    rotord_fault_handler,  // SysTick
};
