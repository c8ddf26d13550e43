# Run with -P after lcm-gen: makes the generated C++ decoders refuse what lcm-gen 1.3.1's accept and then
# misuse. A string's length field counts its terminating NUL, so it must be at least 1: a length of 0 made
# assign() throw std::length_error inside LCM's dispatch (one UDP packet killed imucald), and INT_MIN made
# `len - 1` overflow (undefined behaviour, then a 2 GiB read). A variable array's length is checked against
# the bytes left before resize(), so a forged count cannot allocate gigabytes. Each element takes at least
# one byte, so a count above the bytes left can never decode.
# Usage: cmake -DHEADERS="a.hpp;b.hpp" -P harden_decoders.cmake
foreach(header IN LISTS HEADERS)
  file(READ "${header}" text)
  string(REGEX MATCHALL "\\.assign\\(\\(\\(const char\\*\\)buf\\)" strings "${text}")
  string(REGEX MATCHALL "\\.resize\\(" resizes "${text}")
  string(REGEX REPLACE "if\\((__[A-Za-z0-9_]+) > maxlen - pos\\) return -1;"
         "if(\\1 < 1 || \\1 > maxlen - pos) return -1;" text "${text}")
  string(REGEX REPLACE "this->([A-Za-z0-9_]+)\\.resize\\(this->([A-Za-z0-9_]+)\\);"
         "if(this->\\2 < 0 || this->\\2 > maxlen - pos) return -1;\n    this->\\1.resize(this->\\2);" text "${text}")
  string(REGEX MATCHALL "< 1 \\|\\| __[A-Za-z0-9_]+ > maxlen - pos\\) return -1" guarded_strings "${text}")
  string(REGEX MATCHALL "< 0 \\|\\| this->[A-Za-z0-9_]+ > maxlen - pos\\) return -1" guarded_arrays "${text}")
  list(LENGTH strings n_strings)
  list(LENGTH guarded_strings n_guarded_strings)
  list(LENGTH resizes n_resizes)
  list(LENGTH guarded_arrays n_guarded_arrays)
  # A new lcm-gen that writes its decoders differently must fail the build, not leave them unguarded.
  if(NOT n_strings EQUAL n_guarded_strings OR NOT n_resizes EQUAL n_guarded_arrays)
    message(FATAL_ERROR "${header}: guarded ${n_guarded_strings} of ${n_strings} string decodes and "
                        "${n_guarded_arrays} of ${n_resizes} array resizes: lcm-gen's output changed, update "
                        "lcmtypes/cmake/harden_decoders.cmake")
  endif()
  file(WRITE "${header}" "${text}")
endforeach()
