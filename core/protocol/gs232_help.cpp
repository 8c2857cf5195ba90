#include "protocol/gs232_help.hpp"

namespace rotord::protocol::gs232 {

std::string_view help_page(int page) {
  switch (page) {
    case 1:
      return "---------- COMMAND LIST 1 ----------\r\n"
             "R      turn clockwise\r\n"
             "L      turn counter-clockwise\r\n"
             "A      stop azimuth\r\n"
             "C      report azimuth\r\n"
             "Maaa   turn to azimuth aaa\r\n"
             "Msss aaa aaa ...  timed list, sss seconds per step\r\n"
             "T      start the timed list\r\n"
             "N      timed list: point now and points stored\r\n"
             "X1-X4  azimuth speed, 1 slowest to 4 fastest\r\n"
             "S      stop everything\r\n"
             "O      offset calibration at the CCW stop\r\n"
             "F      full scale calibration at the CW stop\r\n";
    case 2:
      return "---------- COMMAND LIST 2 ----------\r\n"
             "U      turn up\r\n"
             "D      turn down\r\n"
             "E      stop elevation\r\n"
             "B      report elevation\r\n"
             "C2     report azimuth and elevation\r\n"
             "Waaa eee  turn to azimuth aaa, elevation eee\r\n"
             "Wsss aaa eee ...  timed list of pairs\r\n"
             "T      start the timed list\r\n"
             "N      timed list: point now and points stored\r\n"
             "S      stop everything\r\n"
             "O2     elevation offset calibration at the bottom\r\n"
             "F2     elevation full scale calibration at the top\r\n";
    case 3:
      return "---------- COMMAND LIST 3 ----------\r\n"
             "P36    360 degree azimuth scale\r\n"
             "P45    450 degree azimuth scale\r\n"
             "Z      toggle north / south centred needle\r\n";
    default:
      return {};
  }
}

}  // namespace rotord::protocol::gs232
