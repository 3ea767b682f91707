#pragma once
// An FBs PLC served over Modbus (TCP, or RTU on a serial line) as a scenario's LinkedPlc:
// the FBs manual's default map (docs/modbus.md, "Default map") turned around, so that a
// scenario names the PLC's own addresses (X3, R100, DRC200) and each read goes out as few
// FC 01 and FC 03 requests as the map allows (runs of one area, short gaps read through).
// libmodbus frames the requests on the line the io layer holds (io/transport.h), as the
// Modbus bridge does. Modbus has no force and no RUN/STOP status: both are said, not faked.
#include <cstdint>
#include <memory>
#include <string>

#include "plc_cell/io/transport.h"
#include "plc_cell/scenario/linked_plc.h"

typedef struct _modbus modbus_t;

namespace plc_cell {
namespace hardware {

// Where one element of an address sits in the FBs default map: in the coils or the holding
// registers, from `first`, `count` of them (a W view: 16 coils; a 32-bit register: two
// registers, low word first).
struct ModbusPlace {
  bool coils = false;
  uint32_t first = 0;
  uint32_t count = 1;
  uint32_t segment = 0;  // the map's row: a request never spans two
};
// Throws Error saying why a is not in the map.
ModbusPlace fbs_modbus_place(const Address& a);

class ModbusPlc : public scenario::LinkedPlc {
 public:
  // endpoint: HOST:PORT, or DEVICE[:BAUD[:FORMAT]] (9600 8E1 by default) when rtu.
  ModbusPlc(const std::string& endpoint, bool rtu, int unit, int timeout_ms, int retries);
  ~ModbusPlc() override;

  std::string describe() const override { return name_; }
  std::string cannot_reach(const Address& a) const override;
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override;
  std::optional<std::vector<bool>> forced(const std::vector<Address>&) override { return std::nullopt; }
  void write(const Address& a, uint32_t raw) override;
  void force(const Address& bit, bool on) override;
  void unforce(const Address& bit) override { force(bit, false); }
  std::string cannot_force() const override;
  std::optional<RunMode> mode() override { return std::nullopt; }
  std::string cannot_read_mode() const override { return "Modbus does not report RUN or STOP"; }

 private:
  // f(ctx) on the open line, retried as the protocol masters retry (io/transport.h); a
  // failed request throws CommError (after resynchronising the line), an exception reply
  // Error naming it.
  template <class F>
  void transact(const std::string& what, F&& f);

  std::unique_ptr<Transport> t_;
  modbus_t* ctx_ = nullptr;
  std::string name_;
  int timeout_ms_, retries_;
  uint64_t retries_used_ = 0;
};

}  // namespace hardware
}  // namespace plc_cell
