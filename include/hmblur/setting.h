// A setting a user can choose, written once: its name (the command line's --name and the word
// errors use), the methods that read it, what it does, its default, the values it accepts, how
// its text is read into the user's choices, how a choice goes over the settings derived from the
// scene, and how a value is checked. Each group of settings (post-process, hybrid, reference)
// keeps one table of these next to its struct; the command line's options and help are
// generated from the tables and each struct's validate() runs their checks.
#pragma once

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include "hmblur/error.h"

namespace hmb::settings {

template <class Choices, class Settings>
struct Setting {
  std::string_view name;
  std::string_view methods;  // the methods that read it, by name: "postprocess, hybrid"
  std::string_view help;
  std::string defaultText;  // "15", "the scene's", ...: show() of the defaults unless a builder names it
  std::string accepts;      // "1..255", "mcguire|jimenez", ...
  std::string_view valueName;  // what the value is, for help texts: "N", "X", "NAME", "FILE"
  bool flag = false;           // a switch without a value: its text is "true"
  // The text a user typed -> their choice; throws hmb::Error naming the setting.
  std::function<void(Choices&, std::string_view text)> read;
  // The choice, when one was made, over settings derived from the scene.
  std::function<void(const Choices&, Settings&)> apply;
  // Why the value in the settings is not one of `accepts`; empty when it is.
  std::function<std::string(const Settings&)> problem;
  // The value in the settings as text ("none" where unset).
  std::function<std::string(const Settings&)> show;
  // Whether the user made this choice (always false where the choices are the settings themselves).
  std::function<bool(const Choices&)> chosen = [](const Choices&) { return false; };
};

template <class Choices, class Settings>
using Table = std::vector<Setting<Choices, Settings>>;

// Runs every check of a table; throws hmb::Error "<what>: <first problem>".
template <class Choices, class Settings>
void checkAll(const Table<Choices, Settings>& table, const Settings& settings, std::string_view what) {
  for (const auto& setting : table)
    if (const std::string problem = setting.problem(settings); !problem.empty())
      throw Error(std::string(what) + ": " + problem);
}

// Applies every choice a user made over `settings`.
template <class Choices, class Settings>
void applyAll(const Table<Choices, Settings>& table, const Choices& choices, Settings& settings) {
  for (const auto& setting : table) setting.apply(choices, settings);
}

// Whether `method` is one of a setting's methods ("postprocess, hybrid").
inline bool readBy(std::string_view methods, std::string_view method) {
  while (!methods.empty()) {
    const size_t comma = methods.find(',');
    std::string_view name = methods.substr(0, comma);
    while (!name.empty() && name.front() == ' ') name.remove_prefix(1);
    if (name == method) return true;
    methods = comma == std::string_view::npos ? std::string_view() : methods.substr(comma + 1);
  }
  return false;
}

// Throws hmb::Error naming the first choice made that `method` does not read.
template <class Choices, class Settings>
void requireChoicesReadBy(const Table<Choices, Settings>& table, const Choices& choices, std::string_view method) {
  for (const auto& setting : table)
    if (setting.chosen(choices) && !readBy(setting.methods, method))
      throw Error(std::string(setting.name) + " is a setting of " + std::string(setting.methods) + ", not of " +
                  std::string(method));
}

template <class T>
std::string formatNumber(T value) {
  if constexpr (std::is_integral_v<T>) {
    return std::to_string(value);
  } else {
    char text[32];
    std::snprintf(text, sizeof(text), "%g", double(value));
    return text;
  }
}

// The values of an enum and their names.
template <class E>
using Names = std::vector<std::pair<E, std::string_view>>;

template <class E>
std::string_view nameOf(const Names<E>& names, E value) {
  for (const auto& [v, name] : names)
    if (v == value) return name;
  return "?";
}

// The values of a number setting: [min, max] with either end open, odd integers only if asked.
// NaN is never in a range.
template <class T>
struct Range {
  T min = std::numeric_limits<T>::lowest();
  T max = std::numeric_limits<T>::max();
  bool minOpen = false;
  bool maxOpen = false;
  bool oddOnly = false;

  bool contains(T v) const {
    const bool aboveMin = minOpen ? v > min : v >= min;
    const bool belowMax = maxOpen ? v < max : v <= max;
    if constexpr (std::is_integral_v<T>)
      return aboveMin && belowMax && (!oddOnly || v % 2 == 1);
    else
      return aboveMin && belowMax;
  }
  std::string text() const {
    // Appended piece by piece: GCC 12 warns (-Wrestrict) on a literal + std::string temporary.
    std::string text;
    if constexpr (std::is_integral_v<T>) {
      if (oddOnly) text += "odd, ";
      text += formatNumber(min);
      text += "..";
      text += formatNumber(max);
    } else if (max == std::numeric_limits<T>::max()) {
      text += minOpen ? "> " : ">= ";
      text += formatNumber(min);
      text += ", finite";
    } else {
      text += minOpen ? "(" : "[";
      text += formatNumber(min);
      text += ", ";
      text += formatNumber(max);
      text += maxOpen ? ")" : "]";
    }
    return text;
  }
};

template <class T>
struct IsOptional : std::false_type {};
template <class T>
struct IsOptional<std::optional<T>> : std::true_type {};

// A number from the whole of `text`; throws hmb::Error naming the setting.
template <class T>
T parseNumber(std::string_view name, std::string_view text) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  if (error != std::errc() || stop != end || text.empty()) {
    const char* kind = std::is_integral_v<T> ? "a whole number" : "a number";
    throw Error(std::string(name) + ": '" + std::string(text) + "' is not " + kind);
  }
  return value;
}

// What the settings hold for a member that may be unset (std::optional) or not.
template <class Member>
auto valueOf(const Member& member) {
  if constexpr (IsOptional<Member>::value)
    return member;
  else
    return std::optional<Member>(member);
}

// A number setting: the user's choice in choices.*choice (std::optional<T>, or T where the
// choices are the settings), checked and applied at settings.*field (T or std::optional<T>,
// unset meaning a default derived elsewhere, which defaultText must then name).
template <class Choices, class Settings, class T, class ChoiceMember, class FieldMember>
Setting<Choices, Settings> number(std::string_view name, std::string_view methods, std::string_view help,
                                  ChoiceMember Choices::*choice, FieldMember Settings::*field, Range<T> range,
                                  std::string defaultText = {}) {
  Setting<Choices, Settings> s{name, methods, help, std::move(defaultText), range.text(),
                               std::is_integral_v<T> ? "N" : "X"};
  s.read = [=](Choices& c, std::string_view text) { c.*choice = parseNumber<T>(name, text); };
  s.apply = [=](const Choices& c, Settings& settings) {
    if (const auto chosen = valueOf(c.*choice)) settings.*field = *chosen;
  };
  if constexpr (IsOptional<ChoiceMember>::value) s.chosen = [=](const Choices& c) { return (c.*choice).has_value(); };
  s.problem = [=](const Settings& settings) -> std::string {
    const auto value = valueOf(settings.*field);
    if (!value || range.contains(*value)) return {};
    return std::string(name) + " must be " + range.text() + " (got " + formatNumber(T(*value)) + ")";
  };
  s.show = [=](const Settings& settings) {
    const auto value = valueOf(settings.*field);
    return value ? formatNumber(T(*value)) : std::string("none");
  };
  if (s.defaultText.empty()) s.defaultText = s.show(Settings{});
  return s;
}

// A setting that names one of a few values (an enum): `names` lists each value and its name.
template <class Choices, class Settings, class E, class ChoiceMember>
Setting<Choices, Settings> named(std::string_view name, std::string_view methods, std::string_view help,
                                 ChoiceMember Choices::*choice, E Settings::*field,
                                 Names<E> names) {
  std::string accepts;
  for (const auto& entry : names) {
    if (!accepts.empty()) accepts += '|';
    accepts += entry.second;
  }
  Setting<Choices, Settings> s{name, methods, help, "", accepts, "NAME"};
  s.read = [=](Choices& c, std::string_view text) {
    for (const auto& [value, valueName] : names)
      if (valueName == text) {
        c.*choice = value;
        return;
      }
    throw Error("unknown " + std::string(name) + " '" + std::string(text) + "' (" + accepts + ")");
  };
  s.apply = [=](const Choices& c, Settings& settings) {
    if (const auto chosen = valueOf(c.*choice)) settings.*field = *chosen;
  };
  if constexpr (IsOptional<ChoiceMember>::value) s.chosen = [=](const Choices& c) { return (c.*choice).has_value(); };
  s.problem = [=](const Settings& settings) -> std::string {
    for (const auto& entry : names)
      if (entry.first == settings.*field) return {};
    return std::string(name) + " is not one of " + accepts;
  };
  s.show = [=](const Settings& settings) { return std::string(nameOf(names, settings.*field)); };
  s.defaultText = s.show(Settings{});
  return s;
}

// A switch: present means true.
template <class Choices, class Settings>
Setting<Choices, Settings> flag(std::string_view name, std::string_view methods, std::string_view help,
                                bool Choices::*choice, bool Settings::*field) {
  Setting<Choices, Settings> s{name, methods, help, "", "", "", true};
  s.read = [=](Choices& c, std::string_view) { c.*choice = true; };
  s.apply = [=](const Choices& c, Settings& settings) { settings.*field = c.*choice; };
  s.problem = [](const Settings&) { return std::string(); };
  s.show = [=](const Settings& settings) { return std::string(settings.*field ? "on" : "off"); };
  s.defaultText = s.show(Settings{});
  return s;
}

// A file name.
template <class Choices, class Settings>
Setting<Choices, Settings> path(std::string_view name, std::string_view methods, std::string_view help,
                                std::filesystem::path Choices::*choice, std::filesystem::path Settings::*field) {
  Setting<Choices, Settings> s{name, methods, help, "", "a file name", "FILE"};
  s.read = [=](Choices& c, std::string_view value) { c.*choice = std::filesystem::path(std::string(value)); };
  s.apply = [=](const Choices& c, Settings& settings) { settings.*field = c.*choice; };
  s.problem = [](const Settings&) { return std::string(); };
  s.show = [=](const Settings& settings) { return (settings.*field).empty() ? "none" : (settings.*field).string(); };
  s.defaultText = s.show(Settings{});
  return s;
}

}  // namespace hmb::settings
