// Input errors: one clear message naming the file, the key path and what is allowed.
#pragma once
#include <cstdio>
#include <stdexcept>
#include <string>

namespace sonarsim {

/// Bad user input (scene file, mesh, command line). Callers print what() and exit with status 2.
/// what() is always one line: control characters from the input (a key "a\nb", a file name with a tab)
/// are shown escaped, so a hostile or broken file cannot split the message or drive the terminal.
class InputError : public std::runtime_error {
  public:
    InputError(std::string file, std::string key, std::string message)
        : std::runtime_error(compose(file, key, message)), file_(std::move(file)), key_(std::move(key)),
          message_(std::move(message)) {}
    const std::string& file() const { return file_; }
    const std::string& key() const { return key_; }
    const std::string& message() const { return message_; }

    /// `text` with control characters written as \n, \t, \r or \xHH.
    static std::string printable(const std::string& text) {
        std::string s;
        s.reserve(text.size());
        for (const char ch : text) {
            const auto c = static_cast<unsigned char>(ch);
            if (c >= 0x20 && c != 0x7f) {
                s += ch;
            } else if (c == '\n') {
                s += "\\n";
            } else if (c == '\t') {
                s += "\\t";
            } else if (c == '\r') {
                s += "\\r";
            } else {
                char hex[8];
                std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
                s += hex;
            }
        }
        return s;
    }

  private:
    static std::string compose(const std::string& file, const std::string& key, const std::string& msg) {
        std::string s;
        if (!file.empty()) s += file + ": ";
        if (!key.empty()) s += key + ": ";
        return printable(s + msg);
    }
    std::string file_, key_, message_;
};

} // namespace sonarsim
