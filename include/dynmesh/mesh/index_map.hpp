#pragma once
/// \file IndexMap: a hash map from element indices (vertex, edge or face ids) to small
/// values, for algorithms whose cost must follow a region of the mesh rather than the mesh:
/// open addressing with linear probing in two flat arrays, no allocation per element, and
/// clear() in time proportional to the largest size reached, not to the mesh.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace dynmesh {

template <class Value>
class IndexMap {
public:
    using Key = std::uint32_t;
    static constexpr Key kEmpty = std::numeric_limits<Key>::max();  ///< not a valid key

    [[nodiscard]] std::size_t size() const { return size_; }
    [[nodiscard]] bool empty() const { return size_ == 0; }

    /// Removes every entry; keeps the capacity.
    void clear() {
        if (size_ == 0) return;
        std::fill(keys_.begin(), keys_.end(), kEmpty);
        size_ = 0;
    }

    /// Inserts (key, value) unless key is present. Returns the stored value and whether it
    /// was inserted. The pointer is valid until the next insertion. \pre key != kEmpty.
    std::pair<Value*, bool> try_emplace(Key key, Value value) {
        if (2 * (size_ + 1) > keys_.size()) grow();
        std::size_t i = slot(key);
        while (keys_[i] != kEmpty) {
            if (keys_[i] == key) return {&values_[i], false};
            i = (i + 1) & mask_;
        }
        keys_[i] = key;
        values_[i] = std::move(value);
        ++size_;
        return {&values_[i], true};
    }

    [[nodiscard]] const Value* find(Key key) const {
        if (size_ == 0) return nullptr;
        for (std::size_t i = slot(key);; i = (i + 1) & mask_) {
            if (keys_[i] == key) return &values_[i];
            if (keys_[i] == kEmpty) return nullptr;
        }
    }
    [[nodiscard]] bool contains(Key key) const { return find(key) != nullptr; }

    /// Removes key (backward-shift deletion: no tombstones). Returns false when absent.
    bool erase(Key key) {
        if (size_ == 0) return false;
        std::size_t i = slot(key);
        while (keys_[i] != key) {
            if (keys_[i] == kEmpty) return false;
            i = (i + 1) & mask_;
        }
        // Move later entries of the probe run back into the hole when their home slot does
        // not lie cyclically in (hole, j].
        for (std::size_t j = (i + 1) & mask_; keys_[j] != kEmpty; j = (j + 1) & mask_) {
            const std::size_t home = slot(keys_[j]);
            const bool stays = i <= j ? (i < home && home <= j) : (i < home || home <= j);
            if (stays) continue;
            keys_[i] = keys_[j];
            values_[i] = std::move(values_[j]);
            i = j;
        }
        keys_[i] = kEmpty;
        --size_;
        return true;
    }

    /// Calls f(key, value) for every entry, in slot order.
    template <class F>
    void for_each(F&& f) const {
        for (std::size_t i = 0; i < keys_.size(); ++i)
            if (keys_[i] != kEmpty) f(keys_[i], values_[i]);
    }

private:
    [[nodiscard]] std::size_t slot(Key key) const {
        // Fibonacci hashing: the top bits of key * 2^64 / phi.
        return static_cast<std::size_t>((std::uint64_t(key) * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
    }
    void grow() {
        std::vector<Key> keys = std::move(keys_);
        std::vector<Value> values = std::move(values_);
        const std::size_t cap = keys.empty() ? 16 : 2 * keys.size();
        keys_.assign(cap, kEmpty);
        values_.assign(cap, Value());
        mask_ = cap - 1;
        shift_ = 64;
        for (std::size_t c = cap; c > 1; c >>= 1) --shift_;
        size_ = 0;
        for (std::size_t i = 0; i < keys.size(); ++i)
            if (keys[i] != kEmpty) (void)try_emplace(keys[i], std::move(values[i]));
    }

    std::vector<Key> keys_;
    std::vector<Value> values_;
    std::size_t size_ = 0, mask_ = 0;
    unsigned shift_ = 64;
};

/// A set of element indices (IndexMap without values).
class IndexSet {
public:
    /// Inserts key; false when it was present.
    bool insert(std::uint32_t key) { return map_.try_emplace(key, Empty{}).second; }
    bool erase(std::uint32_t key) { return map_.erase(key); }
    [[nodiscard]] bool contains(std::uint32_t key) const { return map_.contains(key); }
    [[nodiscard]] std::size_t size() const { return map_.size(); }
    void clear() { map_.clear(); }
    template <class F>
    void for_each(F&& f) const {
        map_.for_each([&](std::uint32_t k, const Empty&) { f(k); });
    }

private:
    struct Empty {};
    IndexMap<Empty> map_;
};

}  // namespace dynmesh
