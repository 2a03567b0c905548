// Registry: the one table of a kind of plugin (solvers, BSDFs, phase functions), in the shape
// of Mitsuba's plugin manager and Nori's NORI_REGISTER_CLASS, without static initialisers: each
// kind lists its entries in one registry.cpp, in the order help texts show them. An entry is a
// name, a create function that reads the plugin's Params, a help line and an example of its
// parameters, which the registry-driven tests build every entry with.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include "util/params.h"

namespace radkit {

/// A name nobody registered; the message lists the names that are.
class UnknownNameError : public ParamError {
 public:
  using ParamError::ParamError;
};

template <class Product, class... Args>
class Registry {
 public:
  struct Entry {
    const char* name;
    std::unique_ptr<Product> (*create)(Params& params, Args... args);
    const char* help;
    const char* example;  ///< parameters the registry-driven tests build the entry with
  };

  /// kind names the plugins in messages ("solver", "BSDF", "phase function").
  Registry(const char* kind, std::initializer_list<Entry> entries)
      : m_kind(kind), m_entries(entries) {}

  /// \brief The entry called name, or nullptr.
  const Entry* find(const std::string& name) const {
    for (const Entry& e : m_entries)
      if (name == e.name) return &e;
    return nullptr;
  }

  /// \brief The entry called name; throws UnknownNameError listing the known names otherwise.
  const Entry& at(const std::string& name) const {
    if (const Entry* e = find(name)) return *e;
    throw UnknownNameError("unknown " + m_kind + " \"" + name + "\". Fix: use one of " +
                           namesText());
  }

  /// \brief Builds name from params, then rejects the keys its create function did not read.
  ///        Throws UnknownNameError, or ParamError prefixed with the kind and the name
  ///        ('solver "sor": "omega" 2 is outside (0, 2)...').
  std::unique_ptr<Product> make(const std::string& name, Params params, Args... args) const {
    const Entry& e = at(name);
    try {
      std::unique_ptr<Product> product = e.create(params, args...);
      params.rejectUnused(e.name);
      return product;
    } catch (const UnknownNameError&) {
      throw;
    } catch (const ParamError& error) {
      throw ParamError(m_kind + " \"" + e.name + "\": " + error.what());
    }
  }

  const std::vector<Entry>& entries() const { return m_entries; }
  const std::string& kind() const { return m_kind; }

  std::vector<std::string> names() const {
    std::vector<std::string> result;
    for (const Entry& e : m_entries) result.emplace_back(e.name);
    return result;
  }

  /// \brief "a, b, c": the names for messages and help.
  std::string namesText() const {
    std::string text;
    for (const Entry& e : m_entries) text += (text.empty() ? "" : ", ") + std::string(e.name);
    return text;
  }

 private:
  std::string m_kind;
  std::vector<Entry> m_entries;
};

}  // namespace radkit
