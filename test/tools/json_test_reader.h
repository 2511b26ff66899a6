/*
 * SPDX-License-Identifier: BSD-3-Clause
 * Copyright (c) 2026, the pcl_phaser developers.
 *
 * A minimal JSON reader (objects, arrays, strings, numbers, booleans, null) for the
 * tests of pcl_phaser_align --json.
 */
#pragma once

#include <Eigen/Core>

#include <cctype>
#include <cstddef>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

namespace json_test {

struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object } type = Type::Null;
  bool boolean = false;
  double number = 0.0;
  std::string string;
  std::vector<Json> array;
  std::vector<std::pair<std::string, Json>> object;

  /** \brief The member \a key of an object, or nullptr. */
  const Json* get(const std::string& key) const
  {
    for (const auto& m : object)
      if (m.first == key)
        return (&m.second);
    return (nullptr);
  }
  bool isNumber() const { return (type == Type::Number); }
};

class JsonReader {
public:
  explicit JsonReader(const std::string& text)
      : t_(text)
  {
  }

  /** \brief Exactly one value, surrounded by nothing but whitespace. */
  bool document(Json& v)
  {
    if (!value(v))
      return (false);
    skip();
    return (i_ == t_.size());
  }

private:
  void skip()
  {
    while (i_ < t_.size() && std::isspace(static_cast<unsigned char>(t_[i_])))
      ++i_;
  }
  bool eat(char c)
  {
    skip();
    if (i_ < t_.size() && t_[i_] == c) {
      ++i_;
      return (true);
    }
    return (false);
  }
  bool literal(const char* word)
  {
    const std::string w(word);
    if (t_.compare(i_, w.size(), w) != 0)
      return (false);
    i_ += w.size();
    return (true);
  }
  bool str(std::string& s)
  {
    if (!eat('"'))
      return (false);
    while (i_ < t_.size() && t_[i_] != '"') {
      if (t_[i_] == '\\' && ++i_ < t_.size() && t_[i_] == 'u')
        i_ += 4, s += '?';
      else
        s += t_[i_];
      ++i_;
    }
    return (i_ < t_.size() && t_[i_++] == '"');
  }
  bool value(Json& v)
  {
    skip();
    if (i_ >= t_.size())
      return (false);
    const char c = t_[i_];
    if (c == '{') {
      v.type = Json::Type::Object;
      ++i_;
      if (eat('}'))
        return (true);
      do {
        std::string key;
        Json member;
        if (!str(key) || !eat(':') || !value(member))
          return (false);
        v.object.emplace_back(key, member);
      } while (eat(','));
      return (eat('}'));
    }
    if (c == '[') {
      v.type = Json::Type::Array;
      ++i_;
      if (eat(']'))
        return (true);
      do {
        v.array.emplace_back();
        if (!value(v.array.back()))
          return (false);
      } while (eat(','));
      return (eat(']'));
    }
    if (c == '"') {
      v.type = Json::Type::String;
      return (str(v.string));
    }
    if (literal("true") || literal("false")) {
      v.type = Json::Type::Bool;
      v.boolean = c == 't';
      return (true);
    }
    if (literal("null"))
      return (true);
    if (c != '-' && !std::isdigit(static_cast<unsigned char>(c)))
      return (false);
    const char* begin = t_.c_str() + i_;
    char* end = nullptr;
    v.number = std::strtod(begin, &end);
    v.type = Json::Type::Number;
    i_ += static_cast<std::size_t>(end - begin);
    return (end != begin);
  }

  const std::string& t_;
  std::size_t i_ = 0;
};

/** \brief A 4x4 matrix of numbers from nested arrays; false for anything else. */
inline bool toMatrix(const Json* j, Eigen::Matrix4d& m)
{
  if (!j || j->type != Json::Type::Array || j->array.size() != 4)
    return (false);
  for (int r = 0; r < 4; ++r) {
    const Json& row = j->array[r];
    if (row.type != Json::Type::Array || row.array.size() != 4)
      return (false);
    for (int c = 0; c < 4; ++c) {
      if (!row.array[c].isNumber())
        return (false);
      m(r, c) = row.array[c].number;
    }
  }
  return (true);
}

} // namespace json_test
