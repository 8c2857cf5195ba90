# Fails when the C++ exception machinery is in an image or referenced by a
# library. The firmware is built with -fno-exceptions, but a call into
# libstdc++ that may throw (std::string_view::substr's bounds check,
# std::__throw_out_of_range_fmt) or a thread-safe function-local static
# (__cxa_guard_acquire) still links the runtime: __cxa_throw, the personality
# routine and the unwinder, about 9 KB of flash and 4 KB of RAM on the RP2040,
# and a 2.5 KB emergency pool malloc'd at boot. A throw there could only abort.
# Banned by name (issue 15): __cxa_guard_*, __cxa_throw*, __gxx_personality_*,
# __throw_* (std::__throw_length_error and the like), _Unwind_*.
# __cxa_pure_virtual is allowed (the SDK and newlib define it without throwing).
#
#   cmake -DNM=arm-none-eabi-nm "-DFILES=a.elf|lib.a" -P check-no-exceptions.cmake
# An image (.elf) fails if it holds a banned symbol; a library (.a) fails if an
# object defines or refers to one, before --gc-sections could hide it.
cmake_minimum_required(VERSION 3.25)
if(NOT NM OR NOT FILES)
  message(FATAL_ERROR "usage: cmake -DNM=<nm> -DFILES=<file|file...> -P check-no-exceptions.cmake")
endif()
string(REPLACE "|" ";" files "${FILES}")
# On the raw (mangled) names: std::__throw_length_error is _ZSt20__throw_length_errorj.
set(banned "(__cxa_guard_|__cxa_throw|__gxx_personality_|__throw_|_Unwind_)")
set(failed FALSE)
foreach(file IN LISTS files)
  execute_process(COMMAND ${NM} ${file} OUTPUT_VARIABLE symbols COMMAND_ERROR_IS_FATAL ANY)
  string(REPLACE "\n" ";" lines "${symbols}")
  set(member "")
  set(found "")
  foreach(line IN LISTS lines)
    if(line MATCHES "^(.+):$")  # an archive member's heading
      set(member "${CMAKE_MATCH_1}: ")
    elseif(line MATCHES "([^ ]+)$")
      set(name "${CMAKE_MATCH_1}")
      if(name MATCHES "${banned}")
        list(APPEND found "${member}${name}")
      endif()
    endif()
  endforeach()
  if(found)
    list(REMOVE_DUPLICATES found)
    list(LENGTH found count)
    string(REPLACE ";" "\n  " listed "${found}")
    message(SEND_ERROR "${file}: ${count} symbol(s) of the C++ exception runtime:\n  ${listed}\n"
                       "Replace std::string_view::substr with text::slice (core/util/slice.hpp), "
                       "avoid other throwing library calls, and build without thread-safe statics.")
    set(failed TRUE)
  else()
    message(STATUS "${file}: no exception runtime")
  endif()
endforeach()
if(failed)
  message(FATAL_ERROR "exception runtime check failed")
endif()
