#pragma once
/// \file Named, typed per-element property arrays owned by the mesh.
///
/// The mesh owns one container per element kind; adding an element grows every array of that
/// kind at once. Code holds a typed `Property<Handle, T>`, which stays valid while the mesh
/// grows or is garbage-collected, until `remove_property` (or until the mesh is destroyed).

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "dynmesh/error.hpp"

namespace dynmesh {

namespace detail {

class BasePropertyArray {
public:
    explicit BasePropertyArray(std::string name) : name_(std::move(name)) {}
    virtual ~BasePropertyArray() = default;
    virtual void resize(std::size_t n) = 0;
    virtual void push_back() = 0;
    virtual void reserve(std::size_t n) = 0;
    /// Keeps the entries `old_index[i]` at position i, for i < old_index.size().
    virtual void compact(std::span<const std::uint32_t> old_index) = 0;
    [[nodiscard]] virtual std::unique_ptr<BasePropertyArray> clone() const = 0;
    [[nodiscard]] const std::string& name() const { return name_; }

private:
    std::string name_;
};

template <class T>
class PropertyArray final : public BasePropertyArray {
public:
    PropertyArray(std::string name, T default_value)
        : BasePropertyArray(std::move(name)), default_(std::move(default_value)) {}
    void resize(std::size_t n) override { data_.resize(n, default_); }
    void push_back() override { data_.push_back(default_); }
    void reserve(std::size_t n) override { data_.reserve(n); }
    void compact(std::span<const std::uint32_t> old_index) override {
        std::vector<T> out;
        out.reserve(old_index.size());
        for (std::uint32_t i : old_index) out.push_back(data_[i]);
        data_.swap(out);
    }
    [[nodiscard]] std::unique_ptr<BasePropertyArray> clone() const override {
        return std::make_unique<PropertyArray<T>>(*this);
    }
    std::vector<T>& data() { return data_; }
    const std::vector<T>& data() const { return data_; }

private:
    std::vector<T> data_;
    T default_;
};

class PropertyContainer {
public:
    PropertyContainer() = default;
    PropertyContainer(const PropertyContainer& o) { *this = o; }
    PropertyContainer& operator=(const PropertyContainer& o) {
        if (this == &o) return *this;
        arrays_.clear();
        for (const auto& a : o.arrays_) arrays_.push_back(a->clone());
        size_ = o.size_;
        return *this;
    }
    PropertyContainer(PropertyContainer&&) noexcept = default;
    PropertyContainer& operator=(PropertyContainer&&) noexcept = default;

    /// \throw InvalidInput if a property of that name (of any type) is already there.
    template <class T>
    PropertyArray<T>* add(const std::string& name, T default_value) {
        if (find(name) != nullptr) throw InvalidInput("add property: a property named '" + name + "' already exists");
        auto a = std::make_unique<PropertyArray<T>>(name, std::move(default_value));
        a->resize(size_);
        auto* raw = a.get();
        arrays_.push_back(std::move(a));
        return raw;
    }
    template <class T>
    PropertyArray<T>* get(const std::string& name) const {
        return dynamic_cast<PropertyArray<T>*>(find(name));
    }
    BasePropertyArray* find(const std::string& name) const {
        for (const auto& a : arrays_)
            if (a->name() == name) return a.get();
        return nullptr;
    }
    void remove(const BasePropertyArray* a) {
        std::erase_if(arrays_, [a](const auto& p) { return p.get() == a; });
    }
    void push_back() {
        for (auto& a : arrays_) a->push_back();
        ++size_;
    }
    void resize(std::size_t n) {
        for (auto& a : arrays_) a->resize(n);
        size_ = n;
    }
    void reserve(std::size_t n) {
        for (auto& a : arrays_) a->reserve(n);
    }
    void compact(std::span<const std::uint32_t> old_index) {
        for (auto& a : arrays_) a->compact(old_index);
        size_ = old_index.size();
    }
    [[nodiscard]] std::vector<std::string> names() const {
        std::vector<std::string> out;
        for (const auto& a : arrays_) out.push_back(a->name());
        return out;
    }

private:
    std::vector<std::unique_ptr<BasePropertyArray>> arrays_;
    std::size_t size_ = 0;
};

}  // namespace detail

/// A typed view of one property array; index it with the element handle.
template <class HandleT, class T>
class Property {
public:
    Property() = default;
    explicit Property(detail::PropertyArray<T>* a) : array_(a) {}
    [[nodiscard]] bool is_valid() const { return array_ != nullptr; }
    decltype(auto) operator[](HandleT h) { return array_->data()[h.idx()]; }
    decltype(auto) operator[](HandleT h) const {
        return static_cast<const std::vector<T>&>(array_->data())[h.idx()];
    }
    std::vector<T>& vector() { return array_->data(); }
    const std::vector<T>& vector() const { return array_->data(); }
    [[nodiscard]] const detail::BasePropertyArray* array() const { return array_; }

private:
    detail::PropertyArray<T>* array_ = nullptr;
};

}  // namespace dynmesh
