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
  /// an unknown variable. `source` says where the expression came from (file and JSON path), for
  /// the message when it evaluates to a value that is not finite.
  explicit Expression(const std::string& text, std::string source = {});
  /// A constant.
  explicit Expression(Real value);
  ~Expression();
  Expression(const Expression&);
  Expression& operator=(const Expression&) = delete;

  /// The value at time t and reference position x. A value that is not finite ("1/(t-t)",
  /// "0/0", "sqrt(-1)") is a numerical failure: throws NumericalError naming the source and t.
  Real operator()(Real t, const Vec3& x = Vec3::Zero()) const;
  const std::string& text() const { return text_; }
  /// Whether the expression reads x, y or z.
  bool uses_position() const;

 private:
  struct Parser;
  std::string text_, source_;
  std::unique_ptr<Parser> parser_;
};

}  // namespace moreau
