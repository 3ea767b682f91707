// Everything a client sends is hostile: generated requests of random classes (methods,
// paths, headers, bodies, JSON, raw bytes, WebSocket messages), from fixed seeds and a
// bounded loop. The server answers each with a status (or closes), keeps serving, and the
// PLC keeps scanning; a read-only server's memory does not change.
#include <random>

#include "monitor_fixture.h"

namespace plc_cell {
namespace monitor_test {
namespace {

class Gen {
 public:
  explicit Gen(uint32_t seed) : rng_(seed) {}
  size_t pick(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng_); }
  std::string bytes(size_t max) {
    std::string s(pick(max + 1), '\0');
    for (auto& c : s) c = char(pick(256));
    return s;
  }
  std::string of(const std::vector<std::string>& v) { return v[pick(v.size())]; }
  std::string json() {
    switch (pick(6)) {
      case 0: return "{\"address\":" + of({"\"D0\"", "5", "null", "\"\"", "\"X99999\"", "\"D0-D9\""}) +
                     ",\"values\":" + of({"[1]", "[]", "[-99999999999]", "[\"a\"]", "{}", "[1e300]", "[1.5]"}) + "}";
      case 1: return "{\"mode\":" + of({"\"run\"", "\"stop\"", "1", "[]", "\"RUN\""}) + "}";
      case 2: return "{\"address\":\"Y0\",\"action\":" + of({"\"on\"", "\"x\"", "7", "null"}) + "}";
      case 3: return std::string(pick(64), '[') + std::string(pick(64), ']');
      case 4: return "{\"seek_us\":" + of({"-1", "1e99", "\"x\"", "18446744073709551615"}) + "}";
      default: return bytes(200);
    }
  }
  std::string path() {
    static const std::vector<std::string> bases = {"/", "/api/session", "/api/read?a=", "/api/write", "/api/force",
                                                   "/api/mode", "/api/ladder", "/api/status", "/api/coverage",
                                                   "/api/replay", "/assets/", "/vendor/", "/api/live", ""};
    std::string p = of(bases);
    switch (pick(4)) {
      case 0: return p + bytes(40);
      case 1: return p + of({"..", "../..", "%2e%2e/", "D0,X1,%00", std::string(5000, 'a'), "%", "a=,,,,"});
      default: return p;
    }
  }

 private:
  std::mt19937 rng_;
};

TEST_F(MonitorTest, GeneratedHostileRequestsNeverStopTheServerOrTheScan) {
  settings.idle_timeout_us = 300'000;  // raw clients that stall are not waited for long
  serve();
  const std::string t = token();
  const std::string self = "127.0.0.1:" + std::to_string(port);
  for (uint32_t seed = 1; seed <= 120; ++seed) {
    Gen g(seed);
    switch (g.pick(3)) {
      case 0: {  // a well-framed request with hostile parts
        HttpCall c;
        c.method = g.of({"GET", "POST", "PUT", "DELETE", "OPTIONS", "PATCH", "BREW", "HEAD"});
        c.target = g.path();
        if (c.target.empty() || c.target[0] != '/') c.target = "/" + c.target;
        for (auto& ch : c.target) if (ch <= ' ' || ch == 127) ch = 'x';  // the client refuses these
        c.host = g.of({self, "localhost", "evil.example", "[::1]:1", "127.0.0.1:x", ""});
        if (c.host.empty()) c.host = self;
        c.origin = g.of({"", "http://" + self, "null", "http://evil.example"});
        c.token = g.of({"", t, "x"});
        c.body = g.json();
        const auto r = http_call(port, c);
        EXPECT_TRUE(r.status == 0 || (r.status >= 200 && r.status < 600)) << seed;
        if (r.status >= 400) EXPECT_TRUE(r.json().contains("error")) << seed << " " << c.target << " -> " << r.body;
        break;
      }
      case 1: {  // raw bytes, half of them starting like HTTP
        std::string raw = g.pick(2) ? g.of({"GET ", "POST ", "GET / HTTP/1.1\r\n", "X"}) + g.bytes(300) : g.bytes(300);
        raw_exchange(port, raw, std::chrono::milliseconds(800));
        break;
      }
      default: {  // a page sending hostile messages
        WsClient page(port);
        try {
          for (int i = 0; i < 5; ++i) page.send(g.pick(2) ? g.json() : "{\"subscribe\":" + g.json() + "}");
        } catch (const std::exception&) {
          // The server closed a page that sent what a WebSocket may not carry (bad UTF-8).
        }
        break;
      }
    }
    plc.scan(t_us += 1000);
  }
  // Still serving, the scan still ran, and a read-only server changed nothing.
  EXPECT_EQ(http_get(port, "/api/session").status, 200);
  EXPECT_EQ(plc.read(parse_address("D0"), 1)[0], 0u);
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_EQ(http_get(port, "/api/status").json()["scan"]["scans"], 120);
  EXPECT_GT(server->status().rejected, 0u);
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
