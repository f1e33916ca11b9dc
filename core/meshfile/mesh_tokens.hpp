// Tokens of mesh files, for the format checks and readers (mesh_readers.hpp): the failure they report,
// numbers written as whole tokens, lines split into tokens, and tokens quoted for messages.
#pragma once
#include <string>
#include <vector>

namespace sonarsim::mesh_io {

/// A failed check: the message (and the 1-based line in text formats, 0 when unknown). load_mesh turns it
/// into an InputError naming the scene file, the key and the mesh.
struct Problem {
    std::string message;
    long line = 0;
};

[[noreturn]] void fail(const std::string& message, long line = 0);

/// A token from the file for a message: quoted, shortened, bytes outside printable ASCII escaped.
std::string show(const std::string& token);

/// A finite single-precision number in decimal notation, written as the whole token (no hex, inf or nan:
/// OpenMesh's readers would read "0x10" as 0 and carry on).
bool finite_float(const std::string& token);

/// A decimal integer written as the whole token.
bool integer(const std::string& token, long long& value);

/// No NUL and no control characters but whitespace: text, not binary.
bool text_like(const std::string& bytes);

/// Lines of a text file split into whitespace-separated tokens; `#` comments removed when asked.
class TextLines {
  public:
    TextLines(const std::string& text, bool hash_comments) : text_(text), comments_(hash_comments) {}
    /// Next line with at least one token; false at the end.
    bool next(std::vector<std::string>& tokens);
    long line() const { return line_; }

  private:
    const std::string& text_;
    bool comments_;
    size_t pos_ = 0;
    long line_ = 0;
};

} // namespace sonarsim::mesh_io
