#include "rill/rt/load/JsonStructure.h"

#include <nlohmann/json.hpp>

#include <set>
#include <vector>

namespace rt {

namespace {

using json = nlohmann::json;

// The SAX events of one pass: a frame per open object or array, each object's keys so far.
class StructureCheck : public nlohmann::json_sax<json> {
 public:
  explicit StructureCheck(int max_depth) : max_depth_(max_depth) {}
  const std::string& problem() const { return problem_; }

  bool start_object(std::size_t) override { return open(true); }
  bool start_array(std::size_t) override { return open(false); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(string_t& key) override {
    if (!stack_.empty() && !stack_.back().keys.insert(key).second)
      return stop("key '" + key + "' appears twice in " + stack_.back().name);
    pending_ = key;
    return true;
  }
  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception& e) override {
    // nlohmann's message from "parse error" on: its "[json.exception.parse_error.101]"
    // prefix says nothing to a user.
    const std::string msg = e.what();
    const auto p = msg.find("parse error");
    return stop("invalid JSON: " + (p == std::string::npos ? msg : msg.substr(p)));
  }

 private:
  struct Frame {
    bool object = false;
    std::set<std::string> keys;
    std::string name;  // the frame's path: "scene", "materials.m", "lights[]"
  };

  bool open(bool object) {
    // The message names the outermost key the nesting is under, not a path of hundreds of
    // "[]".
    if (static_cast<int>(stack_.size()) >= max_depth_)
      return stop((stack_.size() > 1 ? stack_[1].name : std::string("scene")) +
                  ": JSON nested deeper than " + std::to_string(max_depth_) +
                  " levels (objects and arrays), the most a scene file may nest");
    stack_.push_back(Frame{object, {}, child_name()});
    return true;
  }
  bool close() {
    if (!stack_.empty()) stack_.pop_back();
    return true;
  }
  std::string child_name() const {
    if (stack_.empty()) return "scene";
    const Frame& top = stack_.back();
    // A path past a few hundred characters stops growing ("..."): no scene nests that deep.
    constexpr size_t kLongestPath = 256;
    if (top.name.size() >= kLongestPath)
      return top.name.ends_with("...") ? top.name : top.name + "...";
    return top.object ? (top.name == "scene" ? pending_ : top.name + "." + pending_)
                      : top.name + "[]";
  }
  bool stop(std::string problem) {
    problem_ = std::move(problem);
    return false;
  }

  int max_depth_;
  std::vector<Frame> stack_;
  std::string pending_;  // the last key read, naming what follows
  std::string problem_;
};

}  // namespace

std::string json_structure_problem(const std::string& text, int max_depth) {
  StructureCheck check(max_depth);
  json::sax_parse(text, &check);
  return check.problem();
}

}  // namespace rt
