#include "core/meshfile/mesh_tokens.hpp"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace sonarsim::mesh_io {

void fail(const std::string& message, long line) {
    throw Problem{message, line};
}

std::string show(const std::string& token) {
    std::string s = "\"";
    for (size_t i = 0; i < token.size() && i < 60; ++i) {
        const auto c = static_cast<unsigned char>(token[i]);
        if (c >= 0x20 && c < 0x7f) {
            s += token[i];
        } else {
            char hex[8];
            std::snprintf(hex, sizeof hex, "\\x%02x", unsigned(c));
            s += hex;
        }
    }
    return s + (token.size() > 60 ? "...\"" : "\"");
}

bool finite_float(const std::string& token) {
    if (token.empty() || token.find_first_not_of("0123456789+-.eE") != std::string::npos) return false;
    char* end = nullptr;
    errno = 0;
    const float x = std::strtof(token.c_str(), &end);
    return end == token.c_str() + token.size() && errno != ERANGE && std::isfinite(x);
}

bool integer(const std::string& token, long long& value) {
    if (token.empty()) return false;
    char* end = nullptr;
    errno = 0;
    value = std::strtoll(token.c_str(), &end, 10);
    return end == token.c_str() + token.size() && errno != ERANGE;
}

bool TextLines::next(std::vector<std::string>& tokens) {
    while (pos_ < text_.size()) {
        size_t end = text_.find('\n', pos_);
        if (end == std::string::npos) end = text_.size();
        std::string line = text_.substr(pos_, end - pos_);
        pos_ = end + 1;
        ++line_;
        if (comments_) line = line.substr(0, line.find('#'));
        tokens.clear();
        std::istringstream in(line);
        for (std::string t; in >> t;) tokens.push_back(t);
        if (!tokens.empty()) return true;
    }
    return false;
}

bool text_like(const std::string& bytes) {
    for (unsigned char c : bytes)
        if (c == 0 || (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f' && c != '\v'))
            return false;
    return true;
}

} // namespace sonarsim::mesh_io
