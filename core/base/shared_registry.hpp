// A process-wide table of shared results by key: the first caller computes a key's value, concurrent callers
// of the same key wait for it, and the value lives as long as someone holds it (the table keeps only weak
// references, and forgets keys nothing uses any more). Used for the BVHs and the smooth-normal tables.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <mutex>

namespace sonarsim {

template <typename Key, typename Value> class SharedRegistry {
  public:
    std::shared_ptr<const Value> get(const Key& key,
                                     const std::function<std::shared_ptr<const Value>()>& make) {
        std::shared_ptr<Slot> slot;
        {
            const std::lock_guard<std::mutex> lock(mutex_);
            for (auto it = slots_.begin(); it != slots_.end();) // forget values nothing uses any more
                it = it->second.use_count() == 1 && it->second->value.expired() ? slots_.erase(it)
                                                                                : std::next(it);
            std::shared_ptr<Slot>& s = slots_[key];
            if (!s) s = std::make_shared<Slot>();
            slot = s;
        }
        const std::lock_guard<std::mutex> lock(slot->mutex); // one computation per key; others wait for it
        if (std::shared_ptr<const Value> v = slot->value.lock()) return v;
        std::shared_ptr<const Value> v = make();
        slot->value = v;
        return v;
    }

  private:
    struct Slot {
        std::mutex mutex;
        std::weak_ptr<const Value> value;
    };
    std::mutex mutex_;
    std::map<Key, std::shared_ptr<Slot>> slots_;
};

} // namespace sonarsim
