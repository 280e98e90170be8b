#pragma once
// Settings tables: every field of a settings struct described once, next to the struct: its
// tool key, unit, range and meaning (the default is the struct's initializer). The module's
// run() validates with the table, tools parse `key=value` and list their keys with it, and
// the settings tables in docs/ are generated from it (`obscura settings`). A host
// can build its own panel or config reader on it.
//
// Ranges are written as readers read them: "[1, 1024]", "(0, 1]", "[0, inf)" (an infinite
// bound is open), or the allowed values "1|2|4|8|16". Every value must be finite. Keys are
// the field names in snake case (blurRadius: blur_radius); a nested struct's fields take its
// name as a prefix (temporal.maxFrames: temporal_max_frames), and its `enabled` the name alone
// (temporal.enabled: temporal).
#include "obscura/export.hpp"

#include <glm/vec3.hpp>

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace obscura {

enum class SettingType {
    Flag,     //!< bool; written 1/0, true/false or on/off
    Integer,  //!< int, a whole number in the range
    Unsigned, //!< std::uint32_t
    Real,     //!< float
    Color,    //!< glm::vec3, each channel in the range; written "v" (grey) or "r:g:b"
    Choice,   //!< an enum, written by one of its names
};

//! What a setting is, without how to reach it in its struct.
struct OBSCURA_API SettingDescription {
    std::string field; //!< the C++ member, "radius" or "temporal.maxFrames"
    std::string key;   //!< its tool key, "radius" or "temporal_max_frames"
    SettingType type = SettingType::Real;
    std::string unit;  //!< e.g. "world units", "texels"; empty for plain numbers
    std::string range; //!< as written in the table (Choice: the names joined by '|')
    std::string doc;   //!< one line: what it does
    double min = 0.0, max = 0.0;
    bool minOpen = false, maxOpen = false;
    std::vector<double> allowed; //!< "a|b|c" ranges: the values allowed
    std::vector<std::pair<std::string, int>> choices; //!< Choice: names and enumerator values

    //! Parses `range` (std::logic_error when malformed: a slip in a table).
    SettingDescription(std::string field, SettingType type, std::string unit, std::string range, std::string doc,
                       std::vector<std::pair<std::string, int>> choices = {});
    int channels() const { return type == SettingType::Color ? 3 : 1; }
    //! The tool key of a field name: snake case, '.' as '_' (blurRadius: blur_radius).
    static std::string keyOf(const std::string& field);
    //! Throws Error{InvalidArgument} "<owner>::<field> must be in <range> <unit>, got <value>".
    void check(double value, const std::string& owner) const;
    //! The channels' values of `text`; throws Error{Parse} "<key>=<text>: <why not>".
    std::vector<double> parse(const std::string& text) const;
    //! A value as the tools write it (a Choice's name, a Flag's 0 or 1, "r:g:b").
    std::string format(const std::vector<double>& channels) const;
};

//! One field of S: its description and how to read and write it (per channel, as double).
template <class S>
struct Setting : SettingDescription {
    std::function<double(const S&, int channel)> get;
    std::function<void(S&, int channel, double value)> set;

    std::vector<double> values(const S& s) const {
        std::vector<double> v;
        for (int c = 0; c < channels(); ++c) v.push_back(get(s, c));
        return v;
    }
};

template <class S>
using SettingsTable = std::vector<Setting<S>>;

//! Every field of `s` checked against its row of `table`; throws Error{InvalidArgument}.
template <class S>
void validateSettings(const SettingsTable<S>& table, const S& s, const std::string& owner) {
    for (const Setting<S>& row : table)
        for (const double v : row.values(s)) row.check(v, owner);
}

//! The row whose key is `key`, or null.
template <class S>
const Setting<S>* findSetting(const SettingsTable<S>& table, const std::string& key) {
    for (const Setting<S>& row : table)
        if (row.key == key) return &row;
    return nullptr;
}

//! Sets the field keyed `key` from `text`: false when the table has no such key; throws
//! Error{Parse} for a value it does not accept.
template <class S>
bool applySetting(const SettingsTable<S>& table, S& s, const std::string& key, const std::string& text) {
    const Setting<S>* row = findSetting(table, key);
    if (!row) return false;
    const std::vector<double> v = row->parse(text);
    for (int c = 0; c < row->channels(); ++c) row->set(s, c, v[std::size_t(c)]);
    return true;
}

namespace settings {

// Builders of table rows: the field's name as written in the struct, a pointer to it, then
// unit, range and doc line.

template <class S>
Setting<S> flag(std::string field, bool S::*member, std::string doc) {
    Setting<S> row{{std::move(field), SettingType::Flag, "", "0|1", std::move(doc)}, {}, {}};
    row.get = [member](const S& s, int) { return s.*member ? 1.0 : 0.0; };
    row.set = [member](S& s, int, double v) { s.*member = v != 0.0; };
    return row;
}

template <class S, class T>
Setting<S> number(std::string field, T S::*member, std::string unit, std::string range, std::string doc) {
    static_assert(std::is_same_v<T, int> || std::is_same_v<T, float> || std::is_same_v<T, std::uint32_t>);
    const SettingType type = std::is_same_v<T, float> ? SettingType::Real
                             : std::is_same_v<T, int> ? SettingType::Integer
                                                      : SettingType::Unsigned;
    Setting<S> row{{std::move(field), type, std::move(unit), std::move(range), std::move(doc)}, {}, {}};
    row.get = [member](const S& s, int) { return static_cast<double>(s.*member); };
    row.set = [member](S& s, int, double v) { s.*member = static_cast<T>(v); };
    return row;
}

template <class S>
Setting<S> color(std::string field, glm::vec3 S::*member, std::string unit, std::string range, std::string doc) {
    Setting<S> row{{std::move(field), SettingType::Color, std::move(unit), std::move(range), std::move(doc)}, {}, {}};
    row.get = [member](const S& s, int c) { return static_cast<double>((s.*member)[c]); };
    row.set = [member](S& s, int c, double v) { (s.*member)[c] = static_cast<float>(v); };
    return row;
}

template <class S, class E>
Setting<S> choice(std::string field, E S::*member, std::initializer_list<std::pair<const char*, E>> names,
                  std::string doc) {
    std::vector<std::pair<std::string, int>> choices;
    std::string range;
    for (const auto& [name, value] : names) {
        choices.emplace_back(name, static_cast<int>(value));
        if (!range.empty()) range += '|';
        range += name;
    }
    Setting<S> row{{std::move(field), SettingType::Choice, "", range, std::move(doc), std::move(choices)}, {}, {}};
    row.get = [member](const S& s, int) { return static_cast<double>(static_cast<int>(s.*member)); };
    row.set = [member](S& s, int, double v) { s.*member = static_cast<E>(static_cast<int>(v)); };
    return row;
}

//! The rows of a nested struct's table, reached through `member` and named after `field`.
template <class S, class N>
SettingsTable<S> nested(const std::string& field, N S::*member, const SettingsTable<N>& inner) {
    SettingsTable<S> rows;
    for (const Setting<N>& in : inner) {
        Setting<S> row{static_cast<const SettingDescription&>(in), {}, {}};
        row.field = field + "." + in.field;
        const std::string prefix = SettingDescription::keyOf(field);
        row.key = in.key == "enabled" ? prefix : prefix + "_" + in.key;
        row.get = [member, get = in.get](const S& s, int c) { return get(s.*member, c); };
        row.set = [member, set = in.set](S& s, int c, double v) { set(s.*member, c, v); };
        rows.push_back(std::move(row));
    }
    return rows;
}

//! a followed by b.
template <class S>
SettingsTable<S> join(SettingsTable<S> a, const SettingsTable<S>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

} // namespace settings
} // namespace obscura
