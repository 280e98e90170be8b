#include "obscura/settings_table.hpp"

#include "obscura/error.hpp"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace obscura {
namespace {

std::string snakeCase(const std::string& camel) {
    std::string key;
    for (const char c : camel) {
        if (std::isupper(static_cast<unsigned char>(c))) {
            key += '_';
            key += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        } else {
            key += c == '.' ? '_' : c;
        }
    }
    return key;
}

std::string trim(const std::string& text) {
    const auto first = text.find_first_not_of(' ');
    const auto last = text.find_last_not_of(' ');
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
}

// A bound as written: "inf", "-inf", or a number (the whole text).
double boundValue(const std::string& text, const std::string& range) {
    const std::string t = trim(text);
    if (t == "inf") return std::numeric_limits<double>::infinity();
    if (t == "-inf") return -std::numeric_limits<double>::infinity();
    std::size_t used = 0;
    double v = 0.0;
    try {
        v = std::stod(t, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == 0 || used != t.size()) throw std::logic_error("settings table: bad range \"" + range + "\"");
    return v;
}

std::vector<std::string> split(const std::string& text, const std::string& separators) {
    std::vector<std::string> parts(1);
    for (const char c : text) {
        if (separators.find(c) != std::string::npos) parts.emplace_back();
        else parts.back() += c;
    }
    return parts;
}

// Floats print with the 7 digits they hold (0.05f as 0.05), whole numbers in full.
std::string numberText(double v, bool single = false) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char text[32];
    std::snprintf(text, sizeof text, single ? "%.7g" : "%.10g", v);
    return text;
}

} // namespace

std::string SettingDescription::keyOf(const std::string& field) { return snakeCase(field); }

SettingDescription::SettingDescription(std::string fieldName, SettingType settingType, std::string settingUnit,
                                       std::string settingRange, std::string settingDoc,
                                       std::vector<std::pair<std::string, int>> settingChoices)
    : field(std::move(fieldName)), key(keyOf(field)), type(settingType), unit(std::move(settingUnit)),
      range(std::move(settingRange)), doc(std::move(settingDoc)), choices(std::move(settingChoices)) {
    if (type == SettingType::Choice || type == SettingType::Flag) return;
    if (range.find('|') != std::string::npos) {
        for (const std::string& value : split(range, "|")) allowed.push_back(boundValue(value, range));
        return;
    }
    const std::size_t comma = range.find(',');
    if (range.size() < 5 || comma == std::string::npos || (range.front() != '[' && range.front() != '(') ||
        (range.back() != ']' && range.back() != ')'))
        throw std::logic_error("settings table: bad range \"" + range + "\" for " + field);
    minOpen = range.front() == '(';
    maxOpen = range.back() == ')';
    min = boundValue(range.substr(1, comma - 1), range);
    max = boundValue(range.substr(comma + 1, range.size() - comma - 2), range);
    if ((std::isinf(min) && !minOpen) || (std::isinf(max) && !maxOpen) || !(min <= max))
        throw std::logic_error("settings table: bad range \"" + range + "\" for " + field);
}

void SettingDescription::check(double value, const std::string& owner) const {
    bool ok = std::isfinite(value);
    if (ok && type == SettingType::Choice) {
        ok = false;
        for (const auto& c : choices) ok = ok || value == c.second;
        if (!ok)
            throw Error(ErrorCode::InvalidArgument, owner + "::" + field + " is not one of its enumerators (" + range +
                                                        "), got " + numberText(value));
    } else if (ok && !allowed.empty()) {
        ok = false;
        for (const double a : allowed) ok = ok || value == a;
    } else if (ok && type != SettingType::Flag) {
        ok = (minOpen ? value > min : value >= min) && (maxOpen ? value < max : value <= max);
    }
    if (ok) return;
    const bool single = type == SettingType::Real || type == SettingType::Color;
    throw Error(ErrorCode::InvalidArgument, owner + "::" + field + " must be " + (allowed.empty() ? "in " : "one of ") +
                                                range + (unit.empty() ? "" : " " + unit) + ", got " + numberText(value, single));
}

std::vector<double> SettingDescription::parse(const std::string& text) const {
    const std::string said = key + "=" + text;
    if (type == SettingType::Flag) {
        if (text == "1" || text == "true" || text == "on") return {1.0};
        if (text == "0" || text == "false" || text == "off") return {0.0};
        throw Error(ErrorCode::Parse, said + ": expected 1/0, true/false or on/off");
    }
    if (type == SettingType::Choice) {
        for (const auto& c : choices)
            if (c.first == text) return {double(c.second)};
        throw Error(ErrorCode::Parse, said + ": expected one of " + range);
    }
    // ',' as well as ':' between a colour's channels: bench --variant splits its settings on commas.
    const std::vector<std::string> parts = type == SettingType::Color ? split(text, ":,") : std::vector{text};
    if (parts.size() != 1 && parts.size() != 3)
        throw Error(ErrorCode::Parse, said + ": expected one value (grey) or r:g:b");
    std::vector<double> values;
    for (std::size_t i = 0; i < parts.size(); ++i) {
        const std::string where = parts.size() == 3 ? said + ": " + "rgb"[i] : said;
        double v = 0.0;
        std::size_t used = 0;
        try {
            v = std::stod(parts[i], &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used == 0 || used != parts[i].size()) throw Error(ErrorCode::Parse, where + ": not a number");
        if ((type == SettingType::Integer || type == SettingType::Unsigned) && v != std::floor(v))
            throw Error(ErrorCode::Parse, where + ": must be a whole number");
        // Checked as the field holds it: a float rounds 1e-50 to 0 and 0.99999999 to 1.
        const bool single = type == SettingType::Real || type == SettingType::Color;
        try {
            check(single ? double(float(v)) : v, "");
        } catch (const Error&) {
            throw Error(ErrorCode::Parse, where + ": must be " + (allowed.empty() ? "in " : "one of ") + range +
                                              (unit.empty() ? "" : " " + unit));
        }
        values.push_back(v);
    }
    if (values.size() == 1 && type == SettingType::Color) values.resize(3, values[0]);
    return values;
}

std::string SettingDescription::format(const std::vector<double>& channels) const {
    if (type == SettingType::Flag) return channels.at(0) != 0.0 ? "1" : "0";
    if (type == SettingType::Choice) {
        for (const auto& c : choices)
            if (c.second == channels.at(0)) return c.first;
        return numberText(channels.at(0));
    }
    const bool single = type == SettingType::Real || type == SettingType::Color;
    if (type == SettingType::Color && !(channels[0] == channels[1] && channels[1] == channels[2]))
        return numberText(channels[0], true) + ":" + numberText(channels[1], true) + ":" + numberText(channels[2], true);
    return numberText(channels.at(0), single);
}

} // namespace obscura
