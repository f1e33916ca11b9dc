// Input errors: one clear message naming the file, the key path and what is allowed.
#pragma once
#include <stdexcept>
#include <string>

namespace sonarsim {

/// Bad user input (scene file, mesh, command line). Callers print what() and exit with status 2.
class InputError : public std::runtime_error {
  public:
    InputError(std::string file, std::string key, std::string message)
        : std::runtime_error(compose(file, key, message)), file_(std::move(file)), key_(std::move(key)),
          message_(std::move(message)) {}
    const std::string& file() const { return file_; }
    const std::string& key() const { return key_; }
    const std::string& message() const { return message_; }

  private:
    static std::string compose(const std::string& file, const std::string& key, const std::string& msg) {
        std::string s;
        if (!file.empty()) s += file + ": ";
        if (!key.empty()) s += key + ": ";
        return s + msg;
    }
    std::string file_, key_, message_;
};

} // namespace sonarsim
