// docs/SCENARIOS.md's controller tables against the one listing the reader, the writer and the
// Python bindings walk (ControllerConfig::fields) and against the controller registry: a key that
// is read but documented nowhere, a documented key that nothing reads, or a kind the docs do not
// name fails here.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "floornav/nav/controller.hpp"
#include "floornav/nav/controller_registry.hpp"

namespace floornav {
namespace {

// Dotted keys of a listing: sections as `name.key`, flattened structs at their holder's level.
class KeyLister {
 public:
  KeyLister(std::vector<std::string>& keys, std::string prefix)
      : keys_(keys), prefix_(std::move(prefix)) {}
  template <class Holder, class T>
  void operator()(const char* key, T Holder::*, const char* doc) {
    keys_.push_back(prefix_ + key);
    EXPECT_GT(std::string(doc).size(), 5u) << prefix_ + key << " has no doc in its listing";
  }
  template <class Holder, class S>
  void section(const char* key, S Holder::*) {
    KeyLister sub(keys_, prefix_ + key + ".");
    S::fields(sub);
  }
  template <class Holder, class S>
  void flatten(S Holder::*) {
    S::fields(*this);
  }

 private:
  std::vector<std::string>& keys_;
  std::string prefix_;
};

std::string scenarios_doc() {
  std::ifstream in(FLOORNAV_SCENARIO_DIR "/../docs/SCENARIOS.md");
  EXPECT_TRUE(in) << "docs/SCENARIOS.md not found";
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// The controller section of the docs: `## \`controller\`` up to the next `## ` heading.
struct ControllerDoc {
  std::set<std::string> keys;      ///< first cells of the tables, dotted
  std::string kind_row;            ///< the `kind` row
  std::set<std::string> sections;  ///< `### \`controller.x\`` headings: x
};

// The names in backquotes in `text`, those that look like keys ([a-z_0-9.]+). (No std::regex:
// GCC 12's <regex> trips -Wmaybe-uninitialized in the sanitizer build.)
std::vector<std::string> quoted_names(const std::string& text) {
  std::vector<std::string> names;
  for (std::size_t open = text.find('`'); open != std::string::npos;) {
    const std::size_t close = text.find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string name = text.substr(open + 1, close - open - 1);
    const bool key = !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
      return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
    });
    if (key) {
      names.push_back(name);
      open = text.find('`', close + 1);
    } else {
      open = close;  // the closing quote may open the next name
    }
  }
  return names;
}

ControllerDoc controller_doc() {
  ControllerDoc doc;
  std::istringstream lines(scenarios_doc());
  std::string line, prefix;
  bool inside = false;
  const std::string section_heading = "### `controller.";
  while (std::getline(lines, line)) {
    if (line.rfind("## ", 0) == 0) {
      inside = line == "## `controller`";
      prefix.clear();
      continue;
    }
    if (!inside) continue;
    if (line.rfind(section_heading, 0) == 0) {
      const std::size_t end = line.find('`', section_heading.size());
      const std::string section = line.substr(section_heading.size(), end - section_heading.size());
      prefix = section + ".";
      doc.sections.insert(section);
      continue;
    }
    if (line.rfind("| `", 0) != 0) continue;
    const std::string first = line.substr(1, line.find('|', 1) - 1);
    for (const std::string& name : quoted_names(first)) doc.keys.insert(prefix + name);
    if (prefix.empty() && first.find("`kind`") != std::string::npos) doc.kind_row = line;
  }
  return doc;
}

// In listing order, repeats kept.
std::vector<std::string> listing() {
  std::vector<std::string> keys;
  KeyLister lister(keys, "");
  ControllerConfig::fields(lister);
  return keys;
}
std::set<std::string> listed_keys() {
  const std::vector<std::string> keys = listing();
  return {keys.begin(), keys.end()};
}

TEST(ControllerKeys, EveryKeyReadIsDocumented) {
  const ControllerDoc doc = controller_doc();
  ASSERT_FALSE(doc.keys.empty()) << "no controller table found in docs/SCENARIOS.md";
  for (const std::string& key : listed_keys())
    EXPECT_TRUE(doc.keys.count(key))
        << "controller." << key << " is read but not in docs/SCENARIOS.md's tables";
}

TEST(ControllerKeys, EveryDocumentedKeyIsRead) {
  const std::set<std::string> listed = listed_keys();
  // `kind` and `preset` name things and are read before the listing (io/scenario_file.cpp).
  for (const std::string& key : controller_doc().keys)
    EXPECT_TRUE(listed.count(key) || key == "kind" || key == "preset")
        << "docs/SCENARIOS.md documents controller." << key << ", which nothing reads";
}

TEST(ControllerKeys, TheListingHasNoKeyTwice) {
  // A flattened struct whose key shadows another's would be read into one field only.
  const std::vector<std::string> keys = listing();
  EXPECT_EQ(keys.size(), listed_keys().size());
  // Each layer is there: the chapter's, robot avoidance's, and the three sections.
  for (const char* key : {"v0", "pid.kp", "robot_avoidance", "avoidance_range", "planner.kind",
                          "dwa.horizon", "safety.enabled"})
    EXPECT_EQ(std::count(keys.begin(), keys.end(), key), 1) << key;
}

TEST(ControllerKinds, TheDocsNameEveryRegisteredKindAndItsSection) {
  const ControllerDoc doc = controller_doc();
  ASSERT_FALSE(doc.kind_row.empty());
  ASSERT_FALSE(builtin_controllers().empty());
  for (const BuiltinController& b : builtin_controllers()) {
    std::string quoted;
    quoted.append(1, '`').append(b.name).append(1, '`');
    EXPECT_NE(doc.kind_row.find(quoted), std::string::npos)
        << "the kind row does not name " << b.name;
    EXPECT_FALSE(b.summary.empty()) << b.name;
    ASSERT_NE(b.make, nullptr) << b.name;
    if (!b.params_section.empty()) {
      EXPECT_TRUE(doc.sections.count(std::string(b.params_section)))
          << b.name << "'s parameters (controller." << b.params_section << ") have no table";
    }
  }
}

TEST(ControllerKinds, NamesAreLookedUpExactly) {
  for (const BuiltinController& b : builtin_controllers())
    EXPECT_EQ(find_builtin_controller(b.name), &b);
  EXPECT_EQ(find_builtin_controller("Hybrid"), nullptr);
  EXPECT_EQ(find_builtin_controller(""), nullptr);
  EXPECT_EQ(builtin_controller_choices(), "hybrid, hard_switch, blended, go_to_goal or dwa");
}

}  // namespace
}  // namespace floornav
