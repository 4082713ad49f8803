#include "io/base/text_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include <cerrno>
#include <cstring>

#include <sys/stat.h>
#include <unistd.h>

#include "io/base/error.h"

namespace jgpm {
namespace fs = std::filesystem;

void CheckInputFile(const fs::path& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) {
    ThrowInputError(path.string(), "no such file, expected " + what);
  }
  if (fs::is_directory(status)) {
    ThrowInputError(path.string(), "is a directory, expected a file: " + what);
  }
}

std::string ReadTextFile(const fs::path& path, const std::string& what) {
  CheckInputFile(path, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) ThrowInputError(path.string(), "cannot be opened for reading");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) ThrowInputError(path.string(), "read error");
  std::string text = std::move(buffer).str();
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) {
    ThrowInputError(path.string() + ":1", "file is empty, expected " + what);
  }
  if (const size_t nul = text.find('\0'); nul != std::string::npos) {
    const int line = 1 + static_cast<int>(std::count(text.begin(), text.begin() + nul, '\n'));
    ThrowInputError(path.string() + ":" + std::to_string(line),
                    "binary data (NUL byte), expected " + what);
  }
  return text;
}

fs::path WriteTemporaryBeside(const fs::path& path, const std::string& bytes) {
  const fs::path parent = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(parent, ec)) {
    ThrowInputError(path.string(), "output folder " + parent.string() + " does not exist");
  }
  if (fs::is_directory(path, ec)) {
    ThrowInputError(path.string(), "is a directory, expected an output file name");
  }
  std::string name = path.string() + ".tmp-XXXXXX";
  const int fd = ::mkstemp(name.data());  // a name no other writer has
  if (fd < 0) ThrowInputError(path.string(), std::string("cannot be written (") + std::strerror(errno) + ")");
  // mkstemp makes the file private (0600); give it the permissions any new file gets.
  static const mode_t kUmask = [] {  // read once: umask can only be read by setting it
    const mode_t mask = ::umask(022);
    ::umask(mask);
    return mask;
  }();
  ::fchmod(fd, 0666 & ~kUmask);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    done += static_cast<size_t>(n);
  }
  const bool closed = ::close(fd) == 0;
  if (done != bytes.size() || !closed) {
    fs::remove(name, ec);
    ThrowInputError(path.string(), "write failed (disk full?)");
  }
  return name;
}

void WriteFileAtomic(const fs::path& path, const std::string& text) {
  const fs::path temporary = WriteTemporaryBeside(path, text);
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) {
    fs::remove(temporary, ec);
    ThrowInputError(path.string(), "cannot replace file: " + ec.message());
  }
}

std::vector<std::string_view> SplitBlanks(std::string_view line) {
  std::vector<std::string_view> tokens;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

LineReader::LineReader(std::string_view text, std::string source)
    : text_(text), source_(std::move(source)) {}

bool LineReader::Next() {
  if (pos_ >= text_.size()) return false;
  size_t end = text_.find('\n', pos_);
  if (end == std::string_view::npos) end = text_.size();
  size_t stop = end;
  if (stop > pos_ && text_[stop - 1] == '\r') --stop;
  line_ = text_.substr(pos_, stop - pos_);
  pos_ = end + 1;
  ++line_number_;
  return true;
}

std::string LineReader::Where() const {
  return source_ + ":" + std::to_string(line_number_ == 0 ? 1 : line_number_);
}

void LineReader::Fail(const std::string& what) const { ThrowInputError(Where(), what); }

std::string Quote(std::string_view token) {
  constexpr size_t kMax = 40;
  std::string out = "'";
  for (char c : token.substr(0, kMax)) {
    out += (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f) ? '?' : c;
  }
  if (token.size() > kMax) out += "...";
  return out + "'";
}

namespace {

bool ParseNumber(std::string_view token, double* value) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return false;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, *value);
  return ec == std::errc() && ptr == end;
}

}  // namespace

double LineReader::ParseDouble(std::string_view token, const std::string& what) const {
  double value = 0;
  if (!ParseNumber(token, &value)) Fail("expected a number for " + what + ", found " + Quote(token));
  if (!std::isfinite(value)) {
    Fail("expected a finite number for " + what + ", found " + Quote(token));
  }
  return value;
}

double LineReader::ParseDoubleOrInf(std::string_view token, const std::string& what) const {
  double value = 0;
  if (!ParseNumber(token, &value) || std::isnan(value)) {
    Fail("expected a number or inf for " + what + ", found " + Quote(token));
  }
  return value;
}

int LineReader::ParseInt(std::string_view token, const std::string& what) const {
  int value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || ec != std::errc() || ptr != end) {
    Fail("expected an integer for " + what + ", found " + Quote(token));
  }
  return value;
}

std::string FormatShortest(double value) {
  char buffer[32];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
  JGPM_CHECK(ec == std::errc());
  return std::string(buffer, ptr);
}

}  // namespace jgpm
