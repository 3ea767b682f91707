#pragma once
// The cells of this process (docs/nodelets.md, "One monitor for the process"): each
// plc_node nodelet lists its cell here while it has one, and a monitor nodelet serves them
// all on one port. A listing is an object: its end takes the cell off the list, and every
// watcher has stopped using the cell before that returns, so a cell that goes (a nodelet
// unloaded, ~reset) is never read after it went.
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/runtime/cell.h"

namespace plc_cell {

class CellDirectory {
 public:
  struct Entry {
    uint64_t id;
    std::string name;  // from the node's namespace: /cell_3/plc_node is cell_3
    Cell* cell;
  };
  class Listing {
   public:
    ~Listing();
    Listing(const Listing&) = delete;
    Listing& operator=(const Listing&) = delete;

   private:
    friend class CellDirectory;
    explicit Listing(uint64_t id) : id_(id) {}
    uint64_t id_;
  };
  // What a watcher is told, with the directory's lock held: the cells now (after a cell came
  // or before one goes). It must not call the directory back.
  using Watcher = std::function<void(const std::vector<Entry>& cells)>;

  static CellDirectory& process();

  std::unique_ptr<Listing> list(const std::string& name, Cell& cell);
  // Returns a number for unwatch(); the watcher is told the cells now, at once.
  uint64_t watch(Watcher w);
  void unwatch(uint64_t id);

 private:
  void remove(uint64_t id);
  void tell();  // with mu_ held
  std::mutex mu_;
  uint64_t next_ = 1;
  std::vector<Entry> cells_;
  std::vector<std::pair<uint64_t, Watcher>> watchers_;
};

// A cell's name for the directory, from its node's namespace ("/line/cell_3" -> "cell_3";
// the root namespace: the node's own name): letters, digits, '_' and '-', others as '_'.
std::string directory_name(const std::string& node_namespace, const std::string& node_name);

}  // namespace plc_cell
