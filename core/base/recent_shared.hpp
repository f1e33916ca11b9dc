// A process-wide keep of the few most recently used shared results, by key (thread-safe): for values made
// again frame after frame from the same few inputs that nothing else holds between frames (SharedRegistry
// forgets a value as soon as nobody holds it; this keeps the N most recent).
#pragma once
#include <algorithm>
#include <cstddef>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace sonarsim {

template <typename Key, typename Value, std::size_t N> class RecentShared {
  public:
    /// The value kept for `key`, or make()'s, which is then kept as the most recent. Two threads may both
    /// make a key's value; each gets a valid one.
    template <typename Make> std::shared_ptr<const Value> get(const Key& key, Make&& make) {
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            for (auto it = kept_.begin(); it != kept_.end(); ++it)
                if (it->first == key) {
                    std::rotate(kept_.begin(), it, it + 1);
                    return kept_.front().second;
                }
        }
        std::shared_ptr<const Value> value = make();
        const std::lock_guard<std::mutex> lock(mutex_);
        kept_.emplace(kept_.begin(), key, value);
        if (kept_.size() > N) kept_.pop_back();
        return value;
    }

  private:
    std::mutex mutex_;
    std::vector<std::pair<Key, std::shared_ptr<const Value>>> kept_; ///< most recently used first
};

} // namespace sonarsim
