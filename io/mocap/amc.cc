#include "io/mocap/amc.h"

#include <charconv>
#include <cstdint>
#include <map>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

// A line holding only an integer starts a frame.
// A line holding one integer. Read as 64 bits so that numbers past an int are seen as
// frame numbers (and refused), and the next frame's number never overflows.
bool IsFrameNumber(const std::vector<std::string_view>& tokens, int64_t* number) {
  if (tokens.size() != 1) return false;
  const std::string_view t = tokens[0];
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), *number);
  return ec == std::errc() && ptr == t.data() + t.size();
}

constexpr int64_t kMaxFrameNumber = 1000000000;  // 115 days at 100 fps

std::string DofList(const Bone& bone) {
  std::string list;
  for (Dof dof : bone.dofs) list += (list.empty() ? "" : " ") + std::string(DofName(dof));
  return list;
}

}  // namespace

Motion ParseAmc(std::string_view text, const std::string& source, const Skeleton& skeleton) {
  LineReader in(text, source);
  Motion motion;
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  const int channels = skeleton.NumChannels();
  std::map<std::string, int, std::less<>> bone_index;
  int dof_bones = 0;
  for (size_t b = 0; b < skeleton.bones.size(); ++b) {
    bone_index[skeleton.bones[b].name] = static_cast<int>(b);
    if (!skeleton.bones[b].dofs.empty()) ++dof_bones;
  }

  // Header: comments and the two keywords, up to the first frame number.
  bool fully_specified = false, degrees = false;
  int64_t first_number = 0;
  while (true) {
    if (!in.Next()) {
      in.Fail(fully_specified && degrees ? "expected frames after the header, found none"
                                         : "file ends in the header (no frames)");
    }
    const std::string_view line = in.line();
    const auto tokens = SplitBlanks(line);
    if (tokens.empty()) continue;
    if (tokens[0].front() == '#') {
      motion.header_comments.emplace_back(line);
      continue;
    }
    if (tokens[0] == ":FULLY-SPECIFIED") {
      fully_specified = true;
    } else if (tokens[0] == ":DEGREES") {
      degrees = true;
    } else if (tokens[0] == ":RADIANS") {
      in.Fail("expected :DEGREES (AMC angles in radians are not supported)");
    } else if (IsFrameNumber(tokens, &first_number)) {
      if (first_number > kMaxFrameNumber || first_number < -kMaxFrameNumber) {
        in.Fail("frame number " + std::to_string(first_number) + " is out of range (at most " +
                std::to_string(kMaxFrameNumber) + ")");
      }
      if (!fully_specified) in.Fail("expected :FULLY-SPECIFIED before the first frame");
      if (!degrees) in.Fail("expected :DEGREES before the first frame");
      break;
    } else {
      in.Fail("expected :FULLY-SPECIFIED, :DEGREES or a frame number, found " + Quote(tokens[0]));
    }
  }

  motion.first_frame_number = static_cast<int>(first_number);
  std::vector<double> values;
  values.reserve(static_cast<size_t>(channels) * 512);
  std::vector<int> seen_in_frame(skeleton.bones.size(), 0);
  int64_t frame_number = first_number;
  int frame_line = in.line_number();
  int frames = 0;

  auto finish_frame = [&](bool at_end) {
    int present = 0;
    std::string missing;
    for (size_t b = 0; b < skeleton.bones.size(); ++b) {
      if (skeleton.bones[b].dofs.empty()) continue;
      if (seen_in_frame[b]) {
        ++present;
      } else if (missing.size() < 80) {
        missing += " " + skeleton.bones[b].name;
      }
    }
    if (present != dof_bones) {
      in.Fail((at_end ? "file ends inside frame " : "frame ") + std::to_string(frame_number) +
              " (started at line " + std::to_string(frame_line) + ") lacks " +
              std::to_string(dof_bones - present) + " bone(s):" + missing);
    }
    std::fill(seen_in_frame.begin(), seen_in_frame.end(), 0);
    ++frames;
  };

  values.resize(static_cast<size_t>(channels));
  while (in.Next()) {
    const auto tokens = SplitBlanks(in.line());
    if (tokens.empty()) continue;
    int64_t number = 0;
    if (IsFrameNumber(tokens, &number)) {
      finish_frame(false);
      if (number != frame_number + 1 || number > kMaxFrameNumber) {
        in.Fail("expected frame number " + std::to_string(frame_number + 1) + ", found " +
                std::to_string(number));
      }
      frame_number = number;
      frame_line = in.line_number();
      values.resize(values.size() + channels);
      continue;
    }
    const auto it = bone_index.find(tokens[0]);
    if (it == bone_index.end()) {
      in.Fail("unknown bone " + Quote(tokens[0]) + " (not in the ASF skeleton)");
    }
    const int b = it->second;
    const Bone& bone = skeleton.bones[b];
    if (bone.dofs.empty()) in.Fail("bone '" + bone.name + "' has no dofs in the ASF skeleton");
    if (seen_in_frame[b]) {
      in.Fail("bone '" + bone.name + "' appears twice in frame " + std::to_string(frame_number));
    }
    seen_in_frame[b] = 1;
    if (frames == 0) motion.bone_order.push_back(b);
    if (tokens.size() - 1 != bone.dofs.size()) {
      in.Fail("expected " + std::to_string(bone.dofs.size()) + " value(s) for bone '" + bone.name +
              "' (dof " + DofList(bone) + "), found " + std::to_string(tokens.size() - 1));
    }
    double* row = values.data() + values.size() - channels;
    for (size_t d = 0; d < bone.dofs.size(); ++d) {
      row[offsets[b] + d] = in.ParseDouble(tokens[d + 1], bone.name + "." +
                                                              std::string(DofName(bone.dofs[d])));
    }
  }
  finish_frame(true);

  motion.values = Eigen::Map<const RowMatrixXd>(values.data(), frames, channels);
  return motion;
}

Motion ReadAmc(const std::filesystem::path& path, const Skeleton& skeleton) {
  const std::string text = ReadTextFile(path, "an AMC motion");
  return ParseAmc(text, path.string(), skeleton);
}

std::string FormatAmc(const Motion& motion, const Skeleton& skeleton) {
  JGPM_CHECK(motion.values.cols() == skeleton.NumChannels());
  const std::vector<int> offsets = skeleton.ChannelOffsets();
  std::vector<int> order = motion.bone_order;
  if (order.empty()) {
    for (size_t b = 0; b < skeleton.bones.size(); ++b) {
      if (!skeleton.bones[b].dofs.empty()) order.push_back(static_cast<int>(b));
    }
  }
  std::string out;
  out.reserve(static_cast<size_t>(motion.NumFrames()) * motion.values.cols() * 10);
  for (const std::string& line : motion.header_comments) out += line + "\n";
  out += ":FULLY-SPECIFIED\n:DEGREES\n";
  for (int f = 0; f < motion.NumFrames(); ++f) {
    out += std::to_string(motion.first_frame_number + f) + "\n";
    const double* row = motion.Frame(f);
    for (int b : order) {
      const Bone& bone = skeleton.bones[b];
      out += bone.name;
      for (size_t d = 0; d < bone.dofs.size(); ++d) {
        out += ' ';
        out += FormatShortest(row[offsets[b] + d]);
      }
      out += '\n';
    }
  }
  return out;
}

void WriteAmc(const std::filesystem::path& path, const Motion& motion, const Skeleton& skeleton) {
  WriteFileAtomic(path, FormatAmc(motion, skeleton));
}

}  // namespace jgpm
