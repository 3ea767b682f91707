#pragma once
// Internal to the TRi protocol: the value of one hex digit of a frame (either case), -1 for
// any other character.
namespace plc_cell {
namespace tri {

inline int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace tri
}  // namespace plc_cell
