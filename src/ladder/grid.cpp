// Series parts side by side, parallel parts one under the other: every block's entry and
// exit are on its top row, and whatever touches its left or right edge is its entry or exit
// node, so blocks nest without crossing wires. Outputs sit at the right, one per row; a
// group of outputs that extends the rung above branches off that rung's exit below it.
#include "grid.h"

#include <algorithm>

namespace plc_cell {
namespace ladder {

namespace {

struct Box {
  int w = 1;
  int h = 1;
};

Box measure(const ExprP& e) {
  if (e->kind == Expr::Kind::Contact) return {};
  Box b{0, 0};
  for (const ExprP& p : e->parts) {
    const Box c = measure(p);
    if (e->kind == Expr::Kind::Series) {
      b.w += c.w;
      b.h = std::max(b.h, c.h);
    } else {
      b.w = std::max(b.w, c.w);
      b.h += c.h;
    }
  }
  return b;
}

Box measure_series(const std::vector<ExprP>& parts) {
  Box b{0, 0};
  for (const ExprP& p : parts) {
    const Box c = measure(p);
    b.w += c.w;
    b.h = std::max(b.h, c.h);
  }
  return b;
}

class Grid {
 public:
  Grid(const Drawer& drawer, Network* net) : drawer_(drawer), net_(*net) {}

  int rail() { return node(-1, {}); }

  int node(int contact, std::vector<int> from) {
    net_.nodes.push_back({contact, std::move(from)});
    return static_cast<int>(net_.nodes.size()) - 1;
  }

  Element& element(uint32_t instruction, int row, int col, int in) {
    Element e = drawer_.element(instruction);
    e.id = next_id_++;
    e.row = row;
    e.col = col;
    e.in = in;
    net_.elements.push_back(std::move(e));
    return net_.elements.back();
  }

  void wire(bool vertical, int at, int from, int to, int node) {
    if (from == to) return;
    Wire w;
    w.id = next_id_++;
    w.vertical = vertical;
    (vertical ? w.col : w.row) = at;
    w.from = from;
    w.to = to;
    w.node = node;
    net_.wires.push_back(w);
  }

  // Places e with its entry at (row, boundary col), fed by node `in`; returns its exit node.
  int place(const ExprP& e, int row, int col, int in) {
    if (e->kind == Expr::Kind::Contact) {
      Element& c = element(e->instruction, row, col, in);
      const int id = c.id;
      const int out = node(id, {in});
      net_.elements.back().out = out;
      return out;
    }
    if (e->kind == Expr::Kind::Series) {
      for (const ExprP& p : e->parts) {
        in = place(p, row, col, in);
        col += measure(p).w;
      }
      return in;
    }
    const int width = measure(e).w;
    std::vector<int> outs;
    int top = row, last = row;
    for (const ExprP& p : e->parts) {
      const Box b = measure(p);
      const int out = place(p, top, col, in);
      wire(false, top, col + b.w, col + width, out);
      outs.push_back(out);
      last = top;
      top += b.h;
    }
    const int out = node(-1, outs);
    wire(true, col, row, last, in);
    wire(true, col + width, row, last, out);
    return out;
  }

 private:
  const Drawer& drawer_;
  Network& net_;
  int next_id_ = 0;
};

void draw_fun_inputs(const Rung& rung, const Drawer& drawer, Grid& grid, Network* net) {
  const int rail = grid.rail();
  std::vector<int> outs, tops, exits;
  int rows = 0;
  for (const ExprP& e : rung.fun_inputs) {
    const Box b = measure(e);
    outs.push_back(grid.place(e, rows, 0, rail));
    tops.push_back(rows);
    exits.push_back(b.w);
    rows += b.h;
  }
  const int cols = *std::max_element(exits.begin(), exits.end());
  for (size_t k = 0; k < outs.size(); ++k) grid.wire(false, tops[k], exits[k], cols, outs[k]);
  Element& fun = grid.element(rung.fun, 0, cols, outs[0]);
  const auto names = drawer.fun_inputs(rung.fun, outs.size());
  for (size_t k = 0; k < outs.size(); ++k) fun.inputs.push_back({names[k], tops[k]});
  net->rows = rows;
  net->cols = cols;
}

}  // namespace

void draw_rung(const Rung& rung, const Drawer& drawer, Network* net) {
  Grid grid(drawer, net);
  if (!rung.fun_inputs.empty()) return draw_fun_inputs(rung, drawer, grid, net);
  int cols = 0, exit = 0;
  for (const Group& g : rung.groups) cols = std::max(cols, exit += measure_series(g.extension).w);
  int in = grid.rail(), top = 0, col = 0, rows = 0;
  for (size_t k = 0; k < rung.groups.size(); ++k) {
    const Group& g = rung.groups[k];
    for (const ExprP& p : g.extension) {
      in = grid.place(p, top, col, in);
      col += measure(p).w;
    }
    const int n = static_cast<int>(g.outputs.size());
    for (int j = 0; j < n; ++j) {
      grid.wire(false, top + j, col, cols, in);
      Element& o = grid.element(g.outputs[j], top + j, cols, in);
      if (o.type == "fun") o.inputs.push_back({drawer.fun_inputs(g.outputs[j], 1)[0], top + j});
    }
    rows = std::max(rows, top + std::max(n, measure_series(g.extension).h));
    const int bottom = k + 1 < rung.groups.size() ? top + n : top + n - 1;
    grid.wire(true, col, top, std::max(top, bottom), in);
    top += n;
  }
  net->rows = rows;
  net->cols = cols;
}

void draw_flow(uint32_t instruction, const Drawer& drawer, Network* net) {
  Grid grid(drawer, net);
  grid.element(instruction, 0, 0, -1);
  net->rows = 1;
  net->cols = 0;
}

}  // namespace ladder
}  // namespace plc_cell
