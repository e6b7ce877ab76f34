// The config in the documentation against the real parser, through the public API:
// - every ```yaml block of README.md and docs/*.md is a config that tetray accepts, unless its
//   first line is `# fragment` (a piece of a config, shown to explain a few keys);
// - every key table of docs/config.md (announced by `<!-- keys: PATH ... -->`, PATH a YAML path
//   such as `scenes[0].lights[1]`, `.` for the top level) lists exactly the keys the parser
//   allows there: the test adds `zz_unknown` at each PATH of a full config of docs/config.md
//   and reads the allowed keys from the parser's `unknown key (allowed: ...)` message;
// - every map in those configs has a table, so a new section cannot go undocumented.
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <tetray/adaptor.hpp>

namespace {

namespace fs = std::filesystem;

const fs::path kSourceDir = TETRAY_SOURCE_DIR;

std::vector<std::string> read_lines(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// The markdown files a reader meets: README.md and docs/*.md.
std::vector<fs::path> doc_files() {
  std::vector<fs::path> files{kSourceDir / "README.md"};
  for (const auto& entry : fs::directory_iterator(kSourceDir / "docs")) {
    if (entry.path().extension() == ".md") files.push_back(entry.path());
  }
  std::sort(files.begin() + 1, files.end());
  return files;
}

struct YamlBlock {
  std::string where;  // file:line of the opening fence, for messages
  std::string text;
  bool fragment = false;
};

std::vector<YamlBlock> yaml_blocks(const fs::path& file) {
  std::vector<YamlBlock> blocks;
  const auto lines = read_lines(file);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind("```yaml", 0) != 0) continue;
    YamlBlock block;
    block.where = fs::relative(file, kSourceDir).string() + ":" + std::to_string(i + 1);
    std::size_t j = i + 1;
    for (; j < lines.size() && lines[j].rfind("```", 0) != 0; ++j) block.text += lines[j] + "\n";
    block.fragment = block.text.rfind("# fragment", 0) == 0;
    blocks.push_back(block);
    i = j;
  }
  return blocks;
}

std::vector<YamlBlock> full_configs(const fs::path& file) {
  std::vector<YamlBlock> out;
  for (auto& b : yaml_blocks(file)) {
    if (!b.fragment) out.push_back(b);
  }
  return out;
}

// Each create writes into its own directory (the configs name relative output directories).
class InScratchDir : public ::testing::Test {
 protected:
  void SetUp() override {
    previous_ = fs::current_path();
    dir_ = fs::temp_directory_path() / ("tetray_docs_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    fs::current_path(dir_);
  }
  void TearDown() override {
    fs::current_path(previous_);
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }

 private:
  fs::path previous_, dir_;
};

tetray::Status try_create(const std::string& yaml) {
  tetray::Status status;
  auto adaptor = tetray::Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status);
  if (adaptor) adaptor->finalize();
  return status;
}

using DocsYaml = InScratchDir;

TEST_F(DocsYaml, EveryFullConfigParses) {
  int checked = 0;
  for (const auto& file : doc_files()) {
    for (const auto& block : full_configs(file)) {
      const tetray::Status status = try_create(block.text);
      EXPECT_EQ(status.code, tetray::StatusCode::ok)
          << block.where << ": the config does not parse (mark a piece of a config with a first "
          << "line `# fragment`): " << status.message;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0) << "no ```yaml config found in the docs";
}

// A YAML path: `.` (the top level) or keys and list indices, `scenes[0].lights[1]`.
struct Step {
  std::string key;
  int index = -1;  // -1: a key, else an index into the list under `key`
};

std::vector<Step> parse_path(const std::string& path) {
  std::vector<Step> steps;
  if (path == ".") return steps;
  std::stringstream in(path);
  for (std::string part; std::getline(in, part, '.');) {
    const auto bracket = part.find('[');
    if (bracket == std::string::npos) {
      steps.push_back({part, -1});
    } else {
      steps.push_back({part.substr(0, bracket), std::stoi(part.substr(bracket + 1))});
    }
  }
  return steps;
}

// The map at `path` in `root` (a null node when the path leads elsewhere). A YAML::Node is a
// reference: `reset` moves it to another node, where `=` would overwrite the node it refers to.
YAML::Node node_at(YAML::Node root, const std::string& path) {
  YAML::Node node;
  node.reset(root);
  for (const Step& s : parse_path(path)) {
    if (!node.IsMap()) return {};
    const YAML::Node& as_const = node;
    if (!as_const[s.key]) return {};
    node.reset(node[s.key]);
    if (s.index >= 0) {
      if (!node.IsSequence() || static_cast<std::size_t>(s.index) >= node.size()) return {};
      node.reset(node[static_cast<std::size_t>(s.index)]);
    }
  }
  return node.IsMap() ? node : YAML::Node{};
}

// `scenes[0].lights[1]` -> `scenes[].lights[]`: the section a path belongs to.
std::string section_of(const std::string& path) {
  std::string out;
  bool skipping = false;
  for (char c : path) {
    if (c == '[') {
      out += "[]";
      skipping = true;
    } else if (c == ']') {
      skipping = false;
    } else if (!skipping) {
      out += c;
    }
  }
  return out;
}

struct KeyTable {
  std::string where;
  std::vector<std::string> paths;
  std::set<std::string> keys;
};

// The tables of docs/config.md: a `<!-- keys: PATH... -->` line, then a table whose first column
// holds each key in backticks.
std::vector<KeyTable> key_tables(const fs::path& file) {
  std::vector<KeyTable> tables;
  const auto lines = read_lines(file);
  const std::string marker = "<!-- keys:";
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].rfind(marker, 0) != 0) continue;
    KeyTable table;
    table.where = "docs/config.md:" + std::to_string(i + 1);
    std::stringstream words(lines[i].substr(marker.size()));
    for (std::string w; words >> w && w != "-->";) table.paths.push_back(w);
    std::size_t j = i + 1;
    while (j < lines.size() && lines[j].empty()) ++j;
    int row = 0;
    for (; j < lines.size() && lines[j].rfind("|", 0) == 0; ++j, ++row) {
      if (row < 2) continue;  // the header and its rule
      const auto open = lines[j].find('`');
      const auto close = lines[j].find('`', open + 1);
      const auto cell_end = lines[j].find('|', 1);
      if (open == std::string::npos || close == std::string::npos || open > cell_end) {
        ADD_FAILURE() << "docs/config.md:" << j + 1 << ": a key row without a `key` first";
        continue;
      }
      table.keys.insert(lines[j].substr(open + 1, close - open - 1));
    }
    tables.push_back(table);
    i = j;
  }
  return tables;
}

std::set<std::string> allowed_keys_in(const std::string& message, const std::string& path) {
  const std::string key = path == "." ? "zz_unknown" : path + ".zz_unknown";
  const std::string head = key + ": unknown key (allowed: ";
  const auto at = message.find(head);
  if (at == std::string::npos) return {};
  const auto begin = at + head.size();
  std::stringstream list(message.substr(begin, message.find(')', begin) - begin));
  std::set<std::string> keys;
  for (std::string k; std::getline(list, k, ',');) {
    k.erase(0, k.find_first_not_of(' '));
    keys.insert(k);
  }
  return keys;
}

std::string joined(const std::set<std::string>& keys) {
  std::string out;
  for (const auto& k : keys) out += (out.empty() ? "" : ", ") + k;
  return out;
}

using DocsConfig = InScratchDir;

TEST_F(DocsConfig, EveryTableListsTheKeysTheParserAllows) {
  const fs::path reference = kSourceDir / "docs" / "config.md";
  const auto tables = key_tables(reference);
  const auto configs = full_configs(reference);
  ASSERT_FALSE(tables.empty()) << "no <!-- keys: PATH --> table in docs/config.md";
  for (const KeyTable& table : tables) {
    std::set<std::string> allowed;
    for (const std::string& path : table.paths) {
      const YamlBlock* base = nullptr;
      for (const auto& c : configs) {
        if (node_at(YAML::Load(c.text), path)) {
          base = &c;
          break;
        }
      }
      if (!base) {
        ADD_FAILURE() << table.where << ": no full config in docs/config.md has a map at " << path;
        continue;
      }
      YAML::Node root = YAML::Load(base->text);
      node_at(root, path)["zz_unknown"] = 1;
      const tetray::Status status = try_create(YAML::Dump(root));
      const auto keys = allowed_keys_in(status.message, path);
      if (keys.empty()) {
        ADD_FAILURE() << table.where << ": `zz_unknown` at " << path << " of the config at "
                      << base->where
                      << " did not give `unknown key (allowed: ...)` but: " << status.message;
      }
      allowed.insert(keys.begin(), keys.end());
    }
    std::set<std::string> missing, extra;
    std::set_difference(allowed.begin(), allowed.end(), table.keys.begin(), table.keys.end(),
                        std::inserter(missing, missing.end()));
    std::set_difference(table.keys.begin(), table.keys.end(), allowed.begin(), allowed.end(),
                        std::inserter(extra, extra.end()));
    EXPECT_TRUE(missing.empty()) << table.where << ": the parser accepts keys the table lacks: "
                                 << joined(missing);
    EXPECT_TRUE(extra.empty()) << table.where
                               << ": the table documents keys the parser does not accept: "
                               << joined(extra);
  }
}

// Every map in the docs' full configs has a table of its keys in docs/config.md.
void collect_sections(const YAML::Node& node, const std::string& path, std::set<std::string>& out) {
  if (node.IsMap()) {
    out.insert(path.empty() ? "." : path);
    for (const auto& entry : node) {
      const std::string key = entry.first.Scalar();
      collect_sections(entry.second, path.empty() ? key : path + "." + key, out);
    }
  } else if (node.IsSequence()) {
    for (std::size_t i = 0; i < node.size(); ++i) {
      collect_sections(node[i], path + "[" + std::to_string(i) + "]", out);
    }
  }
}

TEST(DocsConfigSections, EveryMapOfTheDocsConfigsHasATable) {
  std::set<std::string> documented;
  for (const KeyTable& table : key_tables(kSourceDir / "docs" / "config.md")) {
    for (const auto& p : table.paths) documented.insert(section_of(p));
  }
  for (const auto& file : doc_files()) {
    for (const auto& block : full_configs(file)) {
      std::set<std::string> sections;
      collect_sections(YAML::Load(block.text), "", sections);
      for (const auto& s : sections) {
        EXPECT_TRUE(documented.count(section_of(s)))
            << block.where << ": the map at " << s << " has no <!-- keys: --> table in "
            << "docs/config.md";
      }
    }
  }
}

}  // namespace
