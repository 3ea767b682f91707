#pragma once
// FATEK commands 40..53: request and response encoding and parsing, both directions.
// Requests are built by masters (Client) and parsed by slaves (Slave); responses the other way.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/frame.h"

namespace plc_cell {
namespace fatek {

enum class Cmd : uint8_t {
  GistStatus = 0x40,
  RunStop = 0x41,
  Control = 0x42,         // single discrete DISABLE/ENABLE/SET/RESET
  ReadEnable = 0x43,      // ENABLE/DISABLE flags of continuous discretes
  ReadDiscretes = 0x44,
  WriteDiscretes = 0x45,
  ReadRegisters = 0x46,
  WriteRegisters = 0x47,
  MixedRead = 0x48,
  MixedWrite = 0x49,
  Loopback = 0x4E,
  DetailedStatus = 0x53,
};

// The first response data char (spec 1.5).
enum class ErrorCode : char {
  Ok = '0',
  IllegalValue = '2',
  Format = '4',           // illegal format, or command cannot execute
  LadderChecksum = '5',
  IdMismatch = '6',
  Syntax = '7',
  NotSupported = '9',
  IllegalAddress = 'A',
};
const char* error_text(ErrorCode e);
bool is_error_code(char c);

// Action codes of command 42, in the wire order 1..4.
enum class Action : uint8_t { Disable = 1, Enable = 2, Set = 3, Reset = 4 };

// Limits (spec 1.8): items per message.
constexpr uint32_t kMaxDiscretes = 256;      // 43, 44, 45
constexpr uint32_t kMaxWords = 64;           // 46, 47 (16-bit items)
constexpr uint32_t kMaxDWords = 32;          // 46, 47 (32-bit items)
constexpr uint32_t kMaxMixedReadWeight = 64;  // 48: discrete/16-bit = 1, 32-bit = 2
constexpr uint32_t kMaxMixedWriteWeight = 32; // 49
constexpr size_t kMaxLoopback = 256;
constexpr size_t kDetailedStatusBytes = 28;  // cmd 53 layout of spec 1.9 (stjarna)

struct Request {
  uint8_t station = 1;
  Cmd cmd = Cmd::GistStatus;
  bool run = false;                // 41
  Action action = Action::Set;     // 42
  Address start;                   // 42..47 (42: the point)
  uint32_t count = 0;              // 43..47
  std::vector<Address> points;     // 48, 49
  std::vector<uint32_t> values;    // 45, 47, 49
  std::string text;                // 4E
};

struct Response {
  uint8_t station = 1;
  Cmd cmd = Cmd::GistStatus;
  ErrorCode error = ErrorCode::Ok;
  std::vector<uint32_t> values;   // 43, 44, 46, 48 in request order
  std::vector<uint8_t> status;    // 40 (3 bytes), 53 (28 bytes)
  std::string text;               // 4E echo
};

// Weight of one item in 48/49 and the width of its value on the wire.
uint32_t weight(const Address& a);
int value_chars(const Address& a);  // 1, 4 or 8
// Fixed-width wire form of an address (X0016, WY0008, R00012, DWM0000).
std::string wire_address(const Address& a);
// Parses one wire address at the start of s; on success sets *used to its width (5/6/7).
// Returns Ok, Format (malformed) or IllegalAddress (well-formed but outside this PLC).
ErrorCode parse_wire_address(std::string_view s, Address* out, size_t* used);

// Master side. encode_request throws plc_cell::Error on anything the protocol cannot carry.
std::string encode_request(const Request& r);
void check_request(const Request& r);  // same checks, no output
// Parses the response frame to request; on a malformed frame returns false with *why.
bool parse_response(const Request& req, const Frame& f, Response* out, std::string* why);

// Slave side. Fills *out; returns Ok or the error code to answer (Format, IllegalValue,
// IllegalAddress; Format for unknown commands, as the FATEK emulators do).
ErrorCode parse_request(const Frame& f, Request* out);
// The response frame for req (error responses carry no data; 4E echoes without an error char).
std::string encode_response(const Request& req, const Response& r);
void append_response(std::string& out, const Request& req, const Response& r);

}  // namespace fatek
}  // namespace plc_cell
