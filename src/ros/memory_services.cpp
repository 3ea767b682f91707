#include "plc_cell/ros/memory_services.h"

#include <algorithm>
#include <exception>

#include "plc_cell/ForceDiscrete.h"
#include "plc_cell/ReadForced.h"
#include "plc_cell/ReadMemory.h"
#include "plc_cell/ReleaseDiscrete.h"
#include "plc_cell/WriteMemory.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

// A service never throws into roscpp: the failure is the reply.
template <class Res, class F>
bool reply(Res& res, F&& f) {
  try {
    f();
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

Address one_discrete(const MemoryAccess& access, const std::string& what, const std::string& text) {
  const Address a = access.resolve(text);
  if (a.width != Width::Bit) throw Error(what + " " + text + ": only a single discrete can be forced");
  return a;
}

}  // namespace

std::vector<bool> MemoryAccess::forced(const std::vector<Address>&) {
  throw Error("this node does not read which points are forced");
}

std::vector<ros::ServiceServer> advertise_memory_services(ros::NodeHandle& pnh, MemoryAccess& access) {
  MemoryAccess* m = &access;
  std::vector<ros::ServiceServer> out;
  out.push_back(pnh.advertiseService<ReadMemory::Request, ReadMemory::Response>(
      "read", [m](ReadMemory::Request& req, ReadMemory::Response& res) {
        return reply(res, [&] {
          for (uint32_t v : m->read(m->resolve(req.address), req.count == 0 ? 1 : req.count)) res.values.push_back(v);
        });
      }));
  out.push_back(pnh.advertiseService<WriteMemory::Request, WriteMemory::Response>(
      "write", [m](WriteMemory::Request& req, WriteMemory::Response& res) {
        return reply(res, [&] {
          const Address a = m->resolve(req.address);
          std::vector<uint32_t> raw;  // every value checked before anything is written
          for (size_t i = 0; i < req.values.size(); ++i) {
            const Address at = offset_address(a, uint32_t(i));
            try {
              raw.push_back(encode_element(at, req.values[i]));
            } catch (const Error& e) {
              // The element's address says where; a name (a signal, DM[1]) is said too.
              if (req.address == format_address(a)) throw;
              throw Error(req.address + (i ? " + " + std::to_string(i) : "") + " -> " + e.what());
            }
          }
          m->write(a, raw);
        });
      }));
  out.push_back(pnh.advertiseService<ForceDiscrete::Request, ForceDiscrete::Response>(
      "force", [m](ForceDiscrete::Request& req, ForceDiscrete::Response& res) {
        return reply(res, [&] {
          const Address a = one_discrete(*m, "force", req.address);
          m->force(a, req.value);
          res.message = format_address(a) + " forced " + (req.value ? "ON" : "OFF");
        });
      }));
  out.push_back(pnh.advertiseService<ReleaseDiscrete::Request, ReleaseDiscrete::Response>(
      "release", [m](ReleaseDiscrete::Request& req, ReleaseDiscrete::Response& res) {
        return reply(res, [&] {
          std::vector<Address> freed;
          if (req.address.empty()) {
            freed = m->release(nullptr);
          } else {
            const Address a = one_discrete(*m, "release", req.address);
            freed = m->release(&a);
          }
          for (const Address& a : freed) res.released.push_back(format_address(a));
          res.message = freed.empty() ? "nothing was forced" : std::to_string(freed.size()) + " released";
        });
      }));
  if (!access.reads_forced()) return out;
  out.push_back(pnh.advertiseService<ReadForced::Request, ReadForced::Response>(
      "read_forced", [m](ReadForced::Request& req, ReadForced::Response& res) {
        return reply(res, [&] {
          std::vector<Address> bits;  // every name checked before the PLC is asked
          for (const std::string& text : req.addresses) {
            const Address a = m->resolve(text);
            if (a.width != Width::Bit) throw Error("read_forced " + text + ": only a single discrete can be forced");
            bits.push_back(a);
          }
          for (bool f : m->forced(bits)) res.forced.push_back(f);
          res.message = std::to_string(std::count(res.forced.begin(), res.forced.end(), true)) + " of " +
                        std::to_string(bits.size()) + " forced";
        });
      }));
  return out;
}

}  // namespace plc_cell
