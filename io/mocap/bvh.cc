#include "io/mocap/bvh.h"

#include <cmath>
#include <unordered_set>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

constexpr std::string_view kChannelNames[] = {"Xposition", "Yposition", "Zposition",
                                              "Xrotation", "Yrotation", "Zrotation"};

bool ParseChannel(std::string_view text, BvhChannel* channel) {
  for (int i = 0; i < 6; ++i) {
    if (text == kChannelNames[i]) {
      *channel = static_cast<BvhChannel>(i);
      return true;
    }
  }
  return false;
}

bool IsRotationChannel(BvhChannel channel) { return channel >= BvhChannel::kXrotation; }
Axis ChannelAxis(BvhChannel channel) { return static_cast<Axis>(static_cast<int>(channel) % 3); }

// Whitespace-separated tokens across lines, remembering each token's line.
class TokenCursor {
 public:
  explicit TokenCursor(LineReader* in) : in_(in) {}

  // Next token, or empty at the end of the text.
  std::string_view Next() {
    while (index_ >= tokens_.size()) {
      if (!in_->Next()) return {};
      tokens_ = SplitBlanks(in_->line());
      index_ = 0;
    }
    return tokens_[index_++];
  }
  std::string_view NextOrFail(const std::string& expected) {
    const std::string_view token = Next();
    if (token.empty()) in_->Fail("file ends early, expected " + expected);
    return token;
  }
  bool AtLineEnd() const { return index_ >= tokens_.size(); }
  LineReader& reader() { return *in_; }

 private:
  LineReader* in_;
  std::vector<std::string_view> tokens_;
  size_t index_ = 0;
};

void ParseHierarchy(TokenCursor& cursor, Bvh* bvh) {
  LineReader& in = cursor.reader();
  std::string_view token = cursor.NextOrFail("HIERARCHY");
  if (token != "HIERARCHY") in.Fail("expected HIERARCHY, found " + Quote(token));
  token = cursor.NextOrFail("ROOT");
  if (token != "ROOT") in.Fail("expected ROOT, found " + Quote(token));

  // Iterative, so deeply nested input cannot overflow the stack.
  std::vector<int> open;  // joints whose '{' is open
  std::unordered_set<std::string> names;
  bool expect_joint_name = true;
  bool end_site = false;
  while (true) {
    // At the top of the loop the keyword (ROOT, JOINT or End Site) has been consumed.
    BvhJoint joint;
    joint.parent = open.empty() ? -1 : open.back();
    joint.end_site = end_site;
    if (expect_joint_name) {
      const std::string_view name = cursor.NextOrFail("a joint name");
      if (name == "{") in.Fail("expected a joint name before '{'");
      joint.name = std::string(name);
      if (!names.insert(joint.name).second) in.Fail("joint '" + joint.name + "' is defined twice");
    }
    token = cursor.NextOrFail("'{'");
    if (token != "{") in.Fail("expected '{' after the joint name, found " + Quote(token));
    token = cursor.NextOrFail("OFFSET");
    if (token != "OFFSET") in.Fail("expected OFFSET, found " + Quote(token));
    for (int i = 0; i < 3; ++i) {
      joint.offset[i] = in.ParseDouble(cursor.NextOrFail("3 OFFSET values"), "OFFSET");
    }
    if (!end_site) {
      token = cursor.NextOrFail("CHANNELS");
      if (token != "CHANNELS") in.Fail("expected CHANNELS, found " + Quote(token));
      const int count = in.ParseInt(cursor.NextOrFail("a channel count"), "channel count");
      if (count < 0 || count > 6) in.Fail("expected a channel count from 0 to 6");
      for (int i = 0; i < count; ++i) {
        const std::string_view name = cursor.NextOrFail(std::to_string(count) + " channel names");
        BvhChannel channel;
        if (!ParseChannel(name, &channel)) {
          in.Fail("expected a channel name (Xposition ... Zrotation), found " + Quote(name));
        }
        for (BvhChannel other : joint.channels) {
          if (other == channel) in.Fail("channel " + Quote(name) + " is listed twice");
        }
        joint.channels.push_back(channel);
      }
    }
    bvh->joints.push_back(std::move(joint));
    open.push_back(static_cast<int>(bvh->joints.size()) - 1);

    // Children, then '}' (possibly several) until the next JOINT / End Site or the end.
    while (true) {
      token = cursor.NextOrFail("JOINT, End Site or '}'");
      if (token == "}") {
        open.pop_back();
        if (open.empty()) return;
        continue;
      }
      const bool in_end_site = bvh->joints[open.back()].end_site;
      if (token == "JOINT") {
        if (in_end_site) in.Fail("an End Site cannot have children");
        expect_joint_name = true;
        end_site = false;
        break;
      }
      if (token == "End") {
        if (in_end_site) in.Fail("an End Site cannot have children");
        const std::string_view site = cursor.NextOrFail("Site");
        if (site != "Site") in.Fail("expected 'End Site', found 'End " + std::string(site) + "'");
        expect_joint_name = false;
        end_site = true;
        break;
      }
      if (token == "ROOT") in.Fail("expected one ROOT only (a second ROOT inside the hierarchy)");
      if (token == "MOTION") in.Fail("expected '}' to close the hierarchy before MOTION");
      in.Fail("expected JOINT, End Site or '}', found " + Quote(token));
    }
  }
}

std::string_view AfterLabel(const LineReader& in, std::string_view label) {
  std::string_view line = in.line();
  const size_t start = line.find_first_not_of(" \t");
  if (start == std::string_view::npos || line.substr(start, label.size()) != label) {
    in.Fail("expected '" + std::string(label) + "'");
  }
  return line.substr(start + label.size());
}

bool NextNonBlank(LineReader& in) {
  while (in.Next()) {
    if (in.line().find_first_not_of(" \t") != std::string_view::npos) return true;
  }
  return false;
}

}  // namespace

std::string_view BvhChannelName(BvhChannel channel) {
  return kChannelNames[static_cast<int>(channel)];
}

int Bvh::NumChannels() const {
  int n = 0;
  for (const BvhJoint& joint : joints) n += static_cast<int>(joint.channels.size());
  return n;
}

std::vector<int> Bvh::ChannelOffsets() const {
  std::vector<int> offsets(joints.size() + 1, 0);
  for (size_t j = 0; j < joints.size(); ++j) {
    offsets[j + 1] = offsets[j] + static_cast<int>(joints[j].channels.size());
  }
  return offsets;
}

int Bvh::FindJoint(std::string_view name) const {
  for (size_t j = 0; j < joints.size(); ++j) {
    if (!joints[j].end_site && joints[j].name == name) return static_cast<int>(j);
  }
  return -1;
}

Bvh ParseBvh(std::string_view text, const std::string& source, double mm_per_unit) {
  LineReader in(text, source);
  Bvh bvh;
  bvh.mm_per_unit = mm_per_unit;
  TokenCursor cursor(&in);
  ParseHierarchy(cursor, &bvh);
  if (!cursor.AtLineEnd()) in.Fail("expected a new line after the hierarchy's last '}'");

  if (!NextNonBlank(in)) in.Fail("file ends after the hierarchy, expected MOTION");
  const auto motion = SplitBlanks(in.line());
  if (motion.size() != 1 || motion[0] != "MOTION") {
    in.Fail("expected MOTION, found " + Quote(in.line()));
  }
  if (!NextNonBlank(in)) in.Fail("file ends after MOTION, expected 'Frames:'");
  const auto frames_tokens = SplitBlanks(AfterLabel(in, "Frames:"));
  if (frames_tokens.size() != 1) in.Fail("expected one frame count after 'Frames:'");
  const int frames = in.ParseInt(frames_tokens[0], "frame count");
  if (frames < 1) in.Fail("expected a frame count of at least 1, found " + std::to_string(frames));
  if (!NextNonBlank(in)) in.Fail("file ends after 'Frames:', expected 'Frame Time:'");
  const auto time_tokens = SplitBlanks(AfterLabel(in, "Frame Time:"));
  if (time_tokens.size() != 1) in.Fail("expected one value after 'Frame Time:'");
  bvh.frame_time = in.ParseDouble(time_tokens[0], "frame time");
  if (bvh.frame_time <= 0) in.Fail("expected a frame time > 0 seconds");

  const int channels = bvh.NumChannels();
  // The declared count is untrusted until the lines are there: reserve no more than the
  // text can hold (a value takes at least two bytes, digit and separator), then grow.
  std::vector<double> values;
  values.reserve(std::min(static_cast<size_t>(frames) * static_cast<size_t>(channels), text.size() / 2));
  for (int f = 0; f < frames; ++f) {
    if (!NextNonBlank(in)) {
      in.Fail("file ends after " + std::to_string(f) + " of " + std::to_string(frames) +
              " frames");
    }
    const auto tokens = SplitBlanks(in.line());
    if (static_cast<int>(tokens.size()) != channels) {
      in.Fail("expected " + std::to_string(channels) + " channel values in frame " +
              std::to_string(f + 1) + ", found " + std::to_string(tokens.size()));
    }
    for (const std::string_view token : tokens) values.push_back(in.ParseDouble(token, "channel value"));
  }
  if (NextNonBlank(in)) {
    in.Fail("expected the end of the file after the " + std::to_string(frames) +
            " declared frames, found more lines");
  }
  bvh.frames = Eigen::Map<const RowMatrixXd>(values.data(), frames, channels);
  return bvh;
}

Bvh ReadBvh(const std::filesystem::path& path, double mm_per_unit) {
  const std::string text = ReadTextFile(path, "a BVH motion");
  return ParseBvh(text, path.string(), mm_per_unit);
}

std::string FormatBvh(const Bvh& bvh) {
  JGPM_CHECK(!bvh.joints.empty() && bvh.frames.cols() == bvh.NumChannels());
  std::string out = "HIERARCHY\n";
  // Joints are in depth-first pre-order: before a joint, close every open joint that is not
  // its parent.
  std::vector<int> open;
  auto indent = [&](size_t depth) { out.append(depth * 2, ' '); };
  auto close_one = [&] {
    open.pop_back();
    indent(open.size());
    out += "}\n";
  };
  for (size_t j = 0; j < bvh.joints.size(); ++j) {
    const BvhJoint& joint = bvh.joints[j];
    while (!open.empty() && open.back() != joint.parent) close_one();
    JGPM_CHECK((joint.parent < 0) == open.empty());
    indent(open.size());
    out += joint.end_site ? "End Site" : (joint.parent < 0 ? "ROOT " : "JOINT ") + joint.name;
    out += "\n";
    indent(open.size());
    out += "{\n";
    indent(open.size() + 1);
    out += "OFFSET " + FormatShortest(joint.offset.x()) + " " + FormatShortest(joint.offset.y()) +
           " " + FormatShortest(joint.offset.z()) + "\n";
    if (!joint.end_site) {
      indent(open.size() + 1);
      out += "CHANNELS " + std::to_string(joint.channels.size());
      for (BvhChannel c : joint.channels) out += " " + std::string(BvhChannelName(c));
      out += "\n";
    }
    open.push_back(static_cast<int>(j));
  }
  while (!open.empty()) close_one();
  out += "MOTION\nFrames: " + std::to_string(bvh.frames.rows()) + "\n";
  out += "Frame Time: " + FormatShortest(bvh.frame_time) + "\n";
  for (int f = 0; f < bvh.frames.rows(); ++f) {
    for (int c = 0; c < bvh.frames.cols(); ++c) {
      if (c) out += ' ';
      out += FormatShortest(bvh.frames(f, c));
    }
    out += '\n';
  }
  return out;
}

void WriteBvh(const std::filesystem::path& path, const Bvh& bvh) {
  WriteFileAtomic(path, FormatBvh(bvh));
}

void ComputeBvhPose(const Bvh& bvh, int frame, Eigen::Matrix3Xd* joints,
                    std::vector<Eigen::Matrix3d>* rotations) {
  const int n = static_cast<int>(bvh.joints.size());
  const std::vector<int> offsets = bvh.ChannelOffsets();
  std::vector<Eigen::Matrix3d> local;
  std::vector<Eigen::Matrix3d>& global = rotations ? *rotations : local;
  global.resize(n);
  joints->resize(3, n);
  for (int j = 0; j < n; ++j) {
    const BvhJoint& joint = bvh.joints[j];
    Eigen::Vector3d translation = joint.offset;
    Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
    for (size_t c = 0; c < joint.channels.size(); ++c) {
      const double value = bvh.frames(frame, offsets[j] + c);
      if (IsRotationChannel(joint.channels[c])) {
        r = r * AxisRotation(ChannelAxis(joint.channels[c]), value);
      } else {
        translation[static_cast<int>(ChannelAxis(joint.channels[c]))] += value;
      }
    }
    translation *= bvh.mm_per_unit;
    if (joint.parent < 0) {
      global[j] = r;
      joints->col(j) = translation;
    } else {
      global[j] = global[joint.parent] * r;
      joints->col(j) = joints->col(joint.parent) + global[joint.parent] * translation;
    }
  }
}

}  // namespace jgpm
