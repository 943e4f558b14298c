// rill::print: capturing a print into hidden per-element slots, and formatting the slots a
// launch filled (Print.h says what users see).
#include "rill/Print.h"

#include <bit>
#include <charconv>
#include <iostream>

#include "PrintSlots.h"

namespace rill {

namespace {

std::ostream* g_print_output = &std::cout;

// Counts the "{}" of a format (braces doubled are literal); throws on a lone brace.
int count_placeholders(const std::string& f, SourceLoc loc) {
  int n = 0;
  for (size_t i = 0; i < f.size(); ++i) {
    if (f[i] == '{' && i + 1 < f.size() && f[i + 1] == '{') {
      ++i;
    } else if (f[i] == '}' && i + 1 < f.size() && f[i + 1] == '}') {
      ++i;
    } else if (f[i] == '{' && i + 1 < f.size() && f[i + 1] == '}') {
      ++n;
      ++i;
    } else if (f[i] == '{' || f[i] == '}') {
      throw Error("rill::print: the format \"" + f + "\" has a lone '" + f[i] + "' at position " +
                      std::to_string(i) + " (placeholders are {}; write {{ or }} for a brace)",
                  loc);
    }
  }
  return n;
}

ir::Operand int_const(int32_t v, int width) {
  ir::Constant c = detail::splat<int32_t>(v, width);
  return ir::Operand::of_const(c);
}

}  // namespace

std::ostream* set_print_output(std::ostream* os) {
  std::ostream* old = g_print_output;
  g_print_output = os;
  return old;
}

std::ostream* print_output() {
  return g_print_output;
}

namespace detail {

void record_print(const Bool& cond, const PrintFormat& format, const std::vector<PrintArg>& args) {
  const SourceLoc loc = format.loc;
  const int holes = count_placeholders(format.text, loc);
  if (holes != static_cast<int>(args.size()))
    throw Error("rill::print: the format \"" + format.text + "\" has " + std::to_string(holes) +
                    " placeholder(s) {} but " + std::to_string(args.size()) +
                    " argument(s) were given",
                loc);
  std::vector<PrintSite>& sites = print_sites(loc);
  PrintSite site;
  site.format = format.text;
  site.loc = loc;
  const std::string base = "rill$print" + std::to_string(sites.size());
  const ir::Type int1 = ir::int_type(1), bool1{ir::ScalarKind::Bool, 1};

  // count += cond; the arguments are kept where cond holds and the count was still 0, so
  // the slots hold the first run's values (a print in a loop runs many times).
  Ref count = new_hidden_output(int1, base + ".count", loc, &site.count_slot);
  const ir::Operand c = cond.operand(loc);
  const ir::Operand n = operand(count, int1, loc);
  Ref fresh = emit(ir::Op::Eq, bool1, {n, int_const(0, 1)}, loc);
  Ref first = emit(ir::Op::And, bool1, {c, operand(fresh, bool1, loc)}, loc);
  const ir::Operand first_op = operand(first, bool1, loc);
  for (size_t k = 0; k < args.size(); ++k) {
    const ir::Type t = args[k].type;
    const ir::Type it{ir::ScalarKind::Int, t.width};
    ir::Operand bits = args[k].operand;
    if (t.is_float())
      bits = operand(emit(ir::Op::FloatBitsToInt, it, {bits}, loc), it, loc);
    else if (t.kind == ir::ScalarKind::Bool)
      bits = operand(
          emit(ir::Op::Select, it, {bits, int_const(1, t.width), int_const(0, t.width)}, loc), it,
          loc);
    int slot_index = -1;
    Ref slot = new_hidden_output(it, base + ".arg" + std::to_string(k), loc, &slot_index);
    Ref kept = emit(ir::Op::Select, it, {first_op, bits, operand(slot, it, loc)}, loc);
    assign(slot, ir::Mask{}, operand(kept, it, loc), loc);
    site.args.push_back(t);
    site.arg_slots.push_back(slot_index);
  }
  Ref step = emit(ir::Op::Select, int1, {c, int_const(1, 1), int_const(0, 1)}, loc);
  Ref next = emit(ir::Op::Add, int1, {n, operand(step, int1, loc)}, loc);
  assign(count, ir::Mask{}, operand(next, int1, loc), loc);
  sites.push_back(std::move(site));
}

std::string format_value(ir::Type t, const uint32_t* bits) {
  std::string out = t.width > 1 ? "(" : "";
  for (int c = 0; c < t.width; ++c) {
    if (c) out += ", ";
    const uint32_t b = bits[c];
    if (t.is_float()) {
      char buf[32];
      auto r = std::to_chars(buf, buf + sizeof buf, std::bit_cast<float>(b));
      out.append(buf, r.ptr);
    } else if (t.kind == ir::ScalarKind::Int) {
      out += std::to_string(static_cast<int32_t>(b));
    } else {
      out += b ? "true" : "false";
    }
  }
  return out + (t.width > 1 ? ")" : "");
}

std::string format_line(const std::string& format, const std::vector<std::string>& values) {
  std::string out;
  size_t next = 0;
  for (size_t i = 0; i < format.size(); ++i) {
    const char ch = format[i];
    const char after = i + 1 < format.size() ? format[i + 1] : '\0';
    if ((ch == '{' && after == '{') || (ch == '}' && after == '}')) {
      out += ch;
      ++i;
    } else if (ch == '{' && after == '}') {
      out += next < values.size() ? values[next] : std::string("{}");
      ++next;
      ++i;
    } else {
      out += ch;
    }
  }
  return out;
}

std::string format_prints(const std::vector<PrintSite>& sites, const SlotReader& slot,
                          int64_t count, int64_t limit, const std::string& kernel) {
  std::string out;
  int64_t shown = 0, left_out = 0;
  for (int64_t e = 0; e < count; ++e) {
    bool printed = false;
    for (const PrintSite& site : sites) {
      const uint32_t runs = slot(site.count_slot)[e];
      if (runs == 0) continue;
      printed = true;
      if (shown >= limit) break;
      std::vector<std::string> values;
      for (size_t k = 0; k < site.args.size(); ++k) {
        const ir::Type t = site.args[k];
        values.push_back(format_value(t, slot(site.arg_slots[k]) + e * t.width));
      }
      out += format_line(site.format, values);
      if (runs > 1) out += "  [ran " + std::to_string(runs) + " times]";
      out += '\n';
    }
    if (printed) ++(shown >= limit ? left_out : shown);
  }
  if (left_out > 0)
    out += "[rill::print: " + std::to_string(left_out) + " more element(s) of kernel '" + kernel +
           "' printed; Kernel::print_limit or RILL_PRINT_LIMIT (now " + std::to_string(limit) +
           ") shows more]\n";
  return out;
}

}  // namespace detail

}  // namespace rill
