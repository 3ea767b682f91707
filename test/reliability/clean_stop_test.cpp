// SIGTERM/SIGINT at any moment of `plc_cell run`, from right after the spawn to full
// traffic: the process stops cleanly (exit status 0) and the store holds the newest image.
// The moments come from the child's own start-up output (one per line), not from sleeps.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <fstream>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/persist/retentive_image.h"
#include "plc_cell/persist/slot_file.h"
#include "run_child.h"
#include "temp_dir.h"

using namespace plc_cell;

namespace {

const std::vector<AreaRange> kRetentive{{Area::D, 0, 299}};

// The newest valid slot of one store file, decoded; ok = false if the file has none.
Memory newest(const std::string& file, uint64_t* seq, std::vector<uint8_t>* payload) {
  std::vector<std::string> problems;
  Memory m;
  *seq = 0;
  for (const auto& s : persist::read_slots(file, &problems))
    if (s.seq >= *seq) {
      *seq = s.seq;
      *payload = s.payload;
    }
  if (*seq) persist::decode_retentive(*payload, kRetentive, &m);
  return m;
}

TEST(CleanStop, SignalAtEveryStartUpMomentFlushesTheStore) {
  TempDir dir;
  std::ofstream(dir.path() + "/count.il") << "ORG M1925\nINC D=D200\nEND\n";
  const std::string cfg = dir.path() + "/cell.yaml";
  const std::string store = dir.path() + "/store.bin";
  // An interval of a minute: only the stop's own flush can bring the counter to the main file.
  std::ofstream(cfg) << "cell: {name: stop, program: count.il}\n"
                        "plc: {scan_period: 0.001, retentive: [D0-D299]}\n";
  const std::vector<std::string> args = {"--config", cfg, "--persist", store, "--persist-interval", "60s",
                                         "--fatek-tcp", "127.0.0.1:0", "--modbus-tcp", "127.0.0.1:0"};
  std::vector<uint16_t> expected(10, 0);
  int start_lines = 0;  // lines up to "scanning every", learned from the first run
  int clean = 0, before_main = 0, with_writes = 0;
  const int kRuns = 60;
  for (int run = 0; run < kRuns; ++run) {
    // Moments: after `read` lines of output (0 = right after the spawn, start_lines = the
    // whole start-up), or after the start-up and a client's acknowledged writes. Run 0 is
    // of the last kind and learns start_lines.
    const int variant = run == 0 ? -1 : run % (start_lines + 2);
    const bool write_first = variant == -1 || variant == start_lines + 1;
    const int read = write_first ? start_lines : variant;
    const int sig = run % 2 ? SIGINT : SIGTERM;
    SCOPED_TRACE("run " + std::to_string(run) + ", signal after " + std::to_string(read) + " line(s)" +
                 (write_first ? " and writes" : ""));
    RunChild child(args, 0);
    std::string line;
    if (run == 0) {
      do {
        ASSERT_TRUE(child.next_line(&line)) << child.log;
        ++start_lines;
      } while (line.find("scanning every") == std::string::npos);
      ASSERT_GE(start_lines, 4) << child.log;  // persist, two servers, scanning
    }
    for (int k = run == 0 ? read : 0; k < read; ++k) ASSERT_TRUE(child.next_line(&line)) << child.log;
    if (write_first) {
      const auto k = child.log.find("serving FATEK TCP");
      ASSERT_NE(k, std::string::npos) << child.log;
      const int port = std::stoi(child.log.substr(child.log.find("127.0.0.1:", k) + 10));
      fatek::Client c(fatek::tcp_transport("127.0.0.1:" + std::to_string(port)));
      for (int i = 0; i < 10; ++i) expected[i] = uint16_t(run * 100 + i + 1);
      c.write(Address{Area::D, Width::Word, 0}, std::vector<uint32_t>(expected.begin(), expected.end()));
      ++with_writes;
    }
    const int status = child.stop(sig);
    if (read == 0 && WIFSIGNALED(status) && WTERMSIG(status) == sig) {
      // Before the process set up its stop handling (it had printed nothing): the default
      // action, with the store not yet opened. It must still hold the last run's image.
      EXPECT_EQ(child.log, "");
      ++before_main;
    } else {
      ASSERT_TRUE(WIFEXITED(status)) << "status " << status << "\n" << child.log;
      EXPECT_EQ(WEXITSTATUS(status), 0) << child.log;
      EXPECT_NE(child.log.find(sig == SIGINT ? "SIGINT: stopping" : "SIGTERM: stopping"), std::string::npos)
          << child.log;
      ++clean;
    }
    uint64_t main_seq = 0, live_seq = 0;
    std::vector<uint8_t> main_img, live_img;
    const Memory m = newest(store, &main_seq, &main_img);
    newest(store + ".live", &live_seq, &live_img);
    ASSERT_GT(main_seq, 0u);
    for (int i = 0; i < 10; ++i) EXPECT_EQ(m.read(Address{Area::D, Width::Word, uint32_t(i)}), expected[i]) << "D" << i;
    // The final flush: the main file holds the newest image (the live file's), counter included.
    EXPECT_EQ(main_seq, live_seq);
    EXPECT_TRUE(main_img == live_img);
  }
  EXPECT_EQ(clean + before_main, kRuns);
  EXPECT_LE(before_main, (kRuns - 1) / (start_lines + 2));  // only right after the spawn
  EXPECT_GE(with_writes, (kRuns - 1) / (start_lines + 2));
  RecordProperty("clean_stops", clean);
  RecordProperty("stopped_before_main", before_main);
}

}  // namespace
