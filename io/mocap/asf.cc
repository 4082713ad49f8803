#include "io/mocap/asf.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool IsSkippable(std::string_view line) {
  const std::string_view t = Trim(line);
  return t.empty() || t.front() == '#';
}

bool IsSection(std::string_view line) {
  const std::string_view t = Trim(line);
  return !t.empty() && t.front() == ':';
}

Eigen::Vector3d ParseVector3(const LineReader& in, const std::vector<std::string_view>& tokens,
                             size_t first, const std::string& what) {
  if (tokens.size() < first + 3) {
    in.Fail("expected 3 numbers for " + what + ", found " + std::to_string(tokens.size() - first));
  }
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = in.ParseDouble(tokens[first + i], what);
  return v;
}

void ExpectTokenCount(const LineReader& in, const std::vector<std::string_view>& tokens,
                      size_t count, const std::string& what) {
  if (tokens.size() != count) {
    in.Fail("expected " + what + " (" + std::to_string(count - 1) + " value" +
            (count == 2 ? "" : "s") + " after " + Quote(tokens[0]) + "), found " +
            std::to_string(tokens.size() - 1));
  }
}

// Reads "(min max)" pairs from a limits line and the '('-lines after it.
std::vector<DofLimit> ParseLimits(LineReader& in, std::string_view rest, size_t count,
                                  const std::string& bone) {
  std::vector<DofLimit> limits;
  const std::string where = in.Where();  // errors about the count point at the limits line
  auto parse_groups = [&](std::string_view text) {
    text = Trim(text);
    while (!text.empty()) {
      if (text.front() != '(') in.Fail("expected '(' to open a limit pair of bone '" + bone + "'");
      const size_t close = text.find(')');
      if (close == std::string_view::npos) {
        in.Fail("expected ')' to close a limit pair of bone '" + bone + "'");
      }
      const auto values = SplitBlanks(text.substr(1, close - 1));
      if (values.size() != 2) {
        in.Fail("expected 2 numbers (min max) in a limit pair of bone '" + bone + "', found " +
                std::to_string(values.size()));
      }
      DofLimit limit;
      limit.min = in.ParseDoubleOrInf(values[0], "limit minimum");
      limit.max = in.ParseDoubleOrInf(values[1], "limit maximum");
      if (limit.min > limit.max) in.Fail("limit minimum exceeds maximum in bone '" + bone + "'");
      limits.push_back(limit);
      text = Trim(text.substr(close + 1));
    }
  };
  parse_groups(rest);
  while (limits.size() < count) {
    if (!in.Next()) in.Fail("file ends inside the limits of bone '" + bone + "'");
    if (IsSkippable(in.line())) continue;
    if (Trim(in.line()).front() != '(') {
      ThrowInputError(where, "expected " + std::to_string(count) +
                                 " limit pairs for the dofs of bone '" + bone + "', found " +
                                 std::to_string(limits.size()));
    }
    parse_groups(in.line());
  }
  if (limits.size() != count) {
    ThrowInputError(where, "expected " + std::to_string(count) + " limit pairs for the dofs of bone '" + bone +
            "', found " + std::to_string(limits.size()));
  }
  return limits;
}

std::vector<Dof> ParseDofList(const LineReader& in, const std::vector<std::string_view>& tokens,
                              bool root) {
  std::vector<Dof> dofs;
  for (size_t i = 1; i < tokens.size(); ++i) {
    Dof dof;
    if (!ParseDof(tokens[i], &dof)) {
      in.Fail("expected a dof (rx ry rz" + std::string(root ? " tx ty tz" : "") + "), found " +
              Quote(tokens[i]));
    }
    if (!root && !IsRotation(dof)) {
      in.Fail("translation dof " + Quote(tokens[i]) + " is supported on the root only");
    }
    if (std::find(dofs.begin(), dofs.end(), dof) != dofs.end()) {
      in.Fail("dof " + Quote(tokens[i]) + " is listed twice");
    }
    dofs.push_back(dof);
  }
  if (dofs.empty()) in.Fail("expected at least one dof after " + Quote(tokens[0]));
  return dofs;
}

// `name_where` receives the "file:line" of the bone's name.
Bone ParseBone(LineReader& in, double angle_to_deg, std::string* name_where) {
  Bone bone;
  const int begin_line = in.line_number();
  bool has_id = false, has_direction = false, has_length = false, has_axis = false;
  while (true) {
    if (!in.Next()) {
      ThrowInputError(in.source() + ":" + std::to_string(begin_line),
                      "file ends inside a bone block (expected 'end')");
    }
    if (IsSkippable(in.line())) continue;
    const auto tokens = SplitBlanks(in.line());
    const std::string_view key = tokens[0];
    if (key == "end") break;
    if (key == "begin" || IsSection(in.line())) in.Fail("expected 'end' to close the bone block");
    if (key == "id") {
      ExpectTokenCount(in, tokens, 2, "a bone id");
      bone.id = in.ParseInt(tokens[1], "bone id");
      has_id = true;
    } else if (key == "name") {
      ExpectTokenCount(in, tokens, 2, "a bone name");
      bone.name = std::string(tokens[1]);
      *name_where = in.Where();
    } else if (key == "direction") {
      ExpectTokenCount(in, tokens, 4, "a direction");
      bone.direction = ParseVector3(in, tokens, 1, "direction");
      has_direction = true;
    } else if (key == "length") {
      ExpectTokenCount(in, tokens, 2, "a length");
      bone.length = in.ParseDouble(tokens[1], "length");
      if (bone.length < 0) in.Fail("expected a length >= 0, found " + Quote(tokens[1]));
      has_length = true;
    } else if (key == "axis") {
      ExpectTokenCount(in, tokens, 5, "an axis (3 angles and an order such as XYZ)");
      bone.axis_deg = ParseVector3(in, tokens, 1, "axis") * angle_to_deg;
      if (!ParseAxisOrder(tokens[4], &bone.axis_order)) {
        in.Fail("expected an axis order such as XYZ, found " + Quote(tokens[4]));
      }
      has_axis = true;
    } else if (key == "dof") {
      bone.dofs = ParseDofList(in, tokens, /*root=*/false);
    } else if (key == "limits") {
      if (bone.dofs.empty()) in.Fail("expected 'dof' before 'limits'");
      const size_t rest = in.line().find("limits") + 6;
      bone.limits = ParseLimits(in, in.line().substr(rest), bone.dofs.size(),
                                bone.name.empty() ? "?" : bone.name);
      for (DofLimit& limit : bone.limits) {
        limit.min *= angle_to_deg;
        limit.max *= angle_to_deg;
      }
    } else if (key == "bodymass" || key == "cofmass") {
      // Optional Acclaim fields that kinematics does not use.
    } else {
      in.Fail("unknown bone field " + Quote(key) +
              " (expected id, name, direction, length, axis, dof, limits or end)");
    }
  }
  std::string missing;
  if (bone.name.empty()) missing += " name";
  if (!has_direction) missing += " direction";
  if (!has_length) missing += " length";
  if (!has_axis) missing += " axis";
  if (!missing.empty()) {
    in.Fail("bone block" + (bone.name.empty() ? "" : " '" + bone.name + "'") +
            " lacks required field(s):" + missing);
  }
  (void)has_id;
  const double norm = bone.direction.norm();
  if (norm < 1e-9) in.Fail("bone '" + bone.name + "' has a zero direction vector");
  // ASF writes unit directions with 6 digits; normalise so FK bone lengths are exact.
  bone.direction /= norm;
  return bone;
}

}  // namespace

Skeleton ParseAsf(std::string_view text, const std::string& source) {
  LineReader in(text, source);
  Skeleton skeleton;
  std::vector<Bone> bones;  // file order, root excluded
  Bone root;
  root.name = "root";
  bool has_root = false, has_bonedata = false, has_hierarchy = false;
  bool has_angle_unit = false;
  double angle_to_deg = 1.0;
  // (parent, child) pairs in hierarchy order.
  std::vector<std::pair<std::string, std::string>> links;
  std::vector<int> link_lines;

  std::string section;
  while (in.Next()) {
    if (IsSkippable(in.line())) continue;
    const auto tokens = SplitBlanks(in.line());
    if (IsSection(in.line())) {
      section = std::string(tokens[0]);
      if (section == ":version") {
        if (tokens.size() > 1) skeleton.version = std::string(tokens[1]);
      } else if (section == ":name") {
        if (tokens.size() > 1) skeleton.name = std::string(tokens[1]);
      } else if (section == ":root") {
        has_root = true;
      } else if (section == ":bonedata") {
        has_bonedata = true;
      } else if (section == ":hierarchy") {
        has_hierarchy = true;
      } else if (section != ":units" && section != ":documentation") {
        in.Fail("unknown section " + Quote(section) +
                " (expected :version, :name, :units, :documentation, :root, :bonedata or "
                ":hierarchy)");
      }
      continue;
    }
    const std::string_view key = tokens[0];
    if (section == ":units") {
      ExpectTokenCount(in, tokens, 2, "a unit");
      if (key == "mass") {
        skeleton.mass = in.ParseDouble(tokens[1], "mass unit");
      } else if (key == "length") {
        skeleton.length_scale = in.ParseDouble(tokens[1], "length unit");
        if (skeleton.length_scale <= 0) in.Fail("expected a length unit > 0");
      } else if (key == "angle") {
        if (tokens[1] == "deg") {
          angle_to_deg = 1.0;
        } else if (tokens[1] == "rad") {
          angle_to_deg = kRadToDeg;
        } else {
          in.Fail("expected angle unit 'deg' or 'rad', found " + Quote(tokens[1]));
        }
        has_angle_unit = true;
      } else {
        in.Fail("unknown unit " + Quote(key) + " (expected mass, length or angle)");
      }
    } else if (section == ":documentation") {
      // Free text.
    } else if (section == ":root") {
      if (key == "order") {
        root.dofs = ParseDofList(in, tokens, /*root=*/true);
      } else if (key == "axis") {
        ExpectTokenCount(in, tokens, 2, "a root axis order such as XYZ");
        if (!ParseAxisOrder(tokens[1], &root.axis_order)) {
          in.Fail("expected a root axis order such as XYZ, found " + Quote(tokens[1]));
        }
      } else if (key == "position") {
        ExpectTokenCount(in, tokens, 4, "a root position");
        skeleton.root_position = ParseVector3(in, tokens, 1, "root position");
      } else if (key == "orientation") {
        ExpectTokenCount(in, tokens, 4, "a root orientation");
        root.axis_deg = ParseVector3(in, tokens, 1, "root orientation") * angle_to_deg;
      } else {
        in.Fail("unknown root field " + Quote(key) +
                " (expected order, axis, position or orientation)");
      }
    } else if (section == ":bonedata") {
      if (key != "begin") in.Fail("expected 'begin' to open a bone block, found " + Quote(key));
      std::string name_where;
      Bone bone = ParseBone(in, angle_to_deg, &name_where);
      if (bone.name == "root") ThrowInputError(name_where, "a bone may not be called 'root'");
      for (const Bone& other : bones) {
        if (other.name == bone.name) {
          ThrowInputError(name_where, "bone '" + bone.name + "' is defined twice");
        }
      }
      bones.push_back(std::move(bone));
    } else if (section == ":hierarchy") {
      if (key == "begin" || key == "end") {
        if (tokens.size() != 1) in.Fail("expected nothing after " + Quote(key));
        continue;
      }
      if (tokens.size() < 2) in.Fail("expected a parent followed by its children");
      for (size_t i = 1; i < tokens.size(); ++i) {
        links.emplace_back(std::string(tokens[0]), std::string(tokens[i]));
        link_lines.push_back(in.line_number());
      }
    } else {
      in.Fail("expected a section keyword such as :root before " + Quote(key));
    }
  }
  const std::string file_where = source + ":" + std::to_string(std::max(1, in.line_number()));
  if (!has_root) ThrowInputError(file_where, "missing :root section");
  if (!has_bonedata) ThrowInputError(file_where, "missing :bonedata section");
  if (!has_hierarchy) ThrowInputError(file_where, "missing :hierarchy section");
  (void)has_angle_unit;
  if (root.dofs.empty()) ThrowInputError(file_where, ":root has no 'order' line");

  // Link the tree: names -> file indices, 0 is the root.
  std::map<std::string, int, std::less<>> index_of{{"root", 0}};
  for (size_t i = 0; i < bones.size(); ++i) index_of[bones[i].name] = static_cast<int>(i + 1);
  std::vector<int> parent_of(bones.size() + 1, -2);
  std::vector<std::vector<int>> children_of(bones.size() + 1);
  for (size_t l = 0; l < links.size(); ++l) {
    const std::string where = source + ":" + std::to_string(link_lines[l]);
    const auto parent = index_of.find(links[l].first);
    const auto child = index_of.find(links[l].second);
    if (parent == index_of.end()) {
      ThrowInputError(where, "unknown bone " + Quote(links[l].first) + " in :hierarchy");
    }
    if (child == index_of.end()) {
      ThrowInputError(where, "unknown bone " + Quote(links[l].second) + " in :hierarchy");
    }
    if (child->second == 0) ThrowInputError(where, "the root cannot be a child");
    if (parent_of[child->second] != -2) {
      ThrowInputError(where, "bone " + Quote(links[l].second) + " is given a second parent");
    }
    parent_of[child->second] = parent->second;
    children_of[parent->second].push_back(child->second);
  }

  // Depth-first order from the root, so every parent precedes its children.
  std::vector<int> order;
  std::vector<int> stack{0};
  while (!stack.empty()) {
    const int b = stack.back();
    stack.pop_back();
    order.push_back(b);
    for (auto it = children_of[b].rbegin(); it != children_of[b].rend(); ++it) stack.push_back(*it);
  }
  if (order.size() != bones.size() + 1) {
    std::vector<bool> reached(bones.size() + 1, false);
    for (int b : order) reached[b] = true;
    for (size_t i = 1; i < reached.size(); ++i) {
      if (!reached[i]) {
        ThrowInputError(file_where, "bone '" + bones[i - 1].name +
                                        "' is not connected to the root in :hierarchy");
      }
    }
  }
  std::vector<int> new_index(bones.size() + 1);
  for (size_t k = 0; k < order.size(); ++k) new_index[order[k]] = static_cast<int>(k);
  skeleton.bones.resize(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const int old = order[k];
    Bone& bone = skeleton.bones[k];
    bone = old == 0 ? root : std::move(bones[old - 1]);
    bone.parent = old == 0 ? -1 : new_index[parent_of[old]];
    bone.children.clear();
    for (int c : children_of[old]) bone.children.push_back(new_index[c]);
  }
  return skeleton;
}

Skeleton ReadAsf(const std::filesystem::path& path) {
  const std::string text = ReadTextFile(path, "an ASF skeleton");
  return ParseAsf(text, path.string());
}

}  // namespace jgpm
