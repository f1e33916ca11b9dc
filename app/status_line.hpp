// One overwritten status line on stderr, only when stderr is a terminal (logs and pipes stay clean).
#pragma once
#include <cstdio>
#include <string>
#include <unistd.h>

namespace sonarsim::app {

class StatusLine {
  public:
    StatusLine() : tty_(isatty(fileno(stderr)) != 0) {}
    void show(const std::string& text) {
        if (!tty_) return;
        std::fprintf(stderr, "\r\033[K%s", text.c_str());
        std::fflush(stderr);
    }
    void clear() { show(""); }

  private:
    bool tty_;
};

} // namespace sonarsim::app
