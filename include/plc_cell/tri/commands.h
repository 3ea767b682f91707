#pragma once
// TRi host-link commands (manual chapter 16): each command's request and response
// layout, encoded and decoded, for both sides (the slave in slave.h and a master).
// Headers are case-sensitive ("RM" timer PV, "Rm" timer SV). Numbers in the data are
// hex unless noted; timer and counter values are 4 decimal digits, 0000-9999.
// Where the manual's figure was lost, the layout is plc_cell's (docs/tri.md, Decisions).
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace plc_cell {
namespace tri {

enum class Cmd : uint8_t {
  ReadId,          // IR                      -> IR id(2)
  WriteId,         // IW id(2)                -> IW
  ReadInputs,      // RI ch(2)                -> RI byte(2)
  ReadOutputs,     // RO ch(2)                -> RO byte(2)
  ReadRelays,      // RR ch(2)                -> RR byte(2)
  ReadTimerBits,   // RT ch(2)                -> RT byte(2)        (header plc_cell's)
  ReadCounterBits, // RC ch(2)                -> RC byte(2)        (header plc_cell's)
  ReadTimerPv,     // RM nn(2)                -> RM dddd
  ReadTimerSv,     // Rm nn(2)                -> Rm dddd
  ReadCounterPv,   // RU nn(2)                -> RU dddd
  ReadCounterSv,   // Ru nn(2)                -> Ru dddd
  ReadInteger,     // RVI v                   -> RVI hhhhhhhh
  ReadString,      // RV$ v                   -> RV$ text
  ReadDm,          // RVD aaaa                -> RVD hhhh
  ReadSystem,      // RVS tt ii               -> RVS hhhh
  ReadHsc,         // RVH n                   -> RVH hhhhhhhh
  WriteInputs,     // WI ch(2) byte(2)        -> WI                (header plc_cell's)
  WriteOutputs,    // WO ch(2) byte(2)        -> WO
  WriteRelays,     // WR ch(2) byte(2)        -> WR
  WriteTimerBits,  // WT ch(2) byte(2)        -> WT
  WriteCounterBits,// WC ch(2) byte(2)        -> WC
  WriteTimerPv,    // WM nn dddd              -> WM
  WriteTimerSv,    // Wm nn dddd              -> Wm
  WriteCounterPv,  // WU nn dddd              -> WU
  WriteCounterSv,  // Wu nn dddd              -> Wu
  WriteInteger,    // WVI v hhhhhhhh          -> WVI
  WriteString,     // WV$ v text              -> WV$
  WriteDm,         // WVD aaaa hhhh           -> WVD
  WriteSystem,     // WVS tt ii hhhh          -> WVS
  WriteHsc,        // WVH n hhhhhhhh          -> WVH   ("wvH" accepted too)
  ReadAnalog,      // RA nn cc                -> RA {hhhh} x cc    (width plc_cell's)
  WriteAnalog,     // WA nn cc {hhhh} x cc    -> WA cc
  ReadEepromInts,  // RXI aaaa cc             -> RXI {hhhh} x min(cc, 32)
  ReadEepromString,// RX$ aaaa                -> RX$ text
  WriteEepromInts, // WXI aaaa cc {hhhh} x cc -> WXI
  WriteEepromString,// WX$ aaaa text          -> WX$
  ForceBit,        // wb nnnn xx (FF/00)      -> wb    ("Wb" accepted too)
  Halt,            // C2                      -> C2                (plc_cell's)
  Resume,          // C3                      -> C3                (plc_cell's)
};

// Error codes of plc_cell's command-error response "ER cc" (docs/tri.md).
enum class ErrorCode : uint8_t {
  Ok = 0,
  UnknownCommand = 1,  // no such header
  BadData = 2,         // wrong length, not hex / decimal, a value outside its field
  OutOfRange = 3,      // channel, index, address or count the PLC does not have
  NotWritable = 4,     // outside the server's writable ranges
  CannotExecute = 5,   // e.g. resume with no program loaded
};
const char* error_name(ErrorCode e);

struct Request {
  Cmd cmd = Cmd::ReadId;
  std::string header;         // as sent ("wb" or "Wb"); encode_request fills the default
  uint32_t a = 0;             // channel, timer/counter 0-based nn, DM address, type, HSC n,
                              // variable 0-25 (A-Z), EEPROM address, start channel, bit address, ID
  uint32_t b = 0;             // RVS/WVS index, count
  std::vector<uint32_t> values;  // data: byte, value, words, FF/00 as 1/0
  std::string text;           // strings
};

struct Response {
  Cmd cmd = Cmd::ReadId;
  std::string header;
  ErrorCode error = ErrorCode::Ok;
  std::vector<uint32_t> values;  // read data (one per field), WA: the count
  std::string text;
};

// The body (header + data) of a request, e.g. "RVD0E10".
std::string encode_request(const Request& r);
// Parses a request body. On failure returns the code the slave answers with.
ErrorCode parse_request(std::string_view body, Request* out);

// The body of a response to req: "RVD3039", "WVD". An error: "ER" + 2 hex digits.
std::string encode_response(const Request& req, const Response& rsp);
// Parses a response body for req (master side). False when it does not fit req's layout;
// an "ERcc" body is true with rsp->error set.
bool parse_response(const Request& req, std::string_view body, Response* rsp);

// The default header of a command, e.g. "RVD".
const char* header_of(Cmd c);

}  // namespace tri
}  // namespace plc_cell
