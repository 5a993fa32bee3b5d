#pragma once
// Scalar expressions of time and position in scene files ("5*(sin(2*pi*t)+1.1)", "0.1*x*t"),
// compiled once by muparser (Debian's libmuparser) and evaluated many times. Variables: t (s) and
// x, y, z (m, a node's reference position); constants pi and e; muparser's functions (sin, cos,
// exp, sqrt, abs, min, max, ...) and operators, including comparisons ("100*(t<0.5)").
#include <memory>
#include <string>

#include "moreau/math/types.hpp"

namespace moreau {

class Expression {
 public:
  /// Compiles `text`; throws std::invalid_argument with muparser's message on a syntax error or
  /// an unknown variable.
  explicit Expression(const std::string& text);
  /// A constant.
  explicit Expression(Real value);
  ~Expression();
  Expression(const Expression&);
  Expression& operator=(const Expression&) = delete;

  Real operator()(Real t, const Vec3& x = Vec3::Zero()) const;
  const std::string& text() const { return text_; }
  /// Whether the expression reads x, y or z.
  bool uses_position() const;

 private:
  struct Parser;
  std::string text_;
  std::unique_ptr<Parser> parser_;
};

}  // namespace moreau
