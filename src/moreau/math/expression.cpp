#include "moreau/math/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <cmath>
#include <stdexcept>

#include "moreau/errors.hpp"

namespace moreau {

// muparser reads variables through pointers bound at definition, so each parser owns its
// variables; evaluation writes them and is therefore not thread-safe (moreau evaluates serially).
struct Expression::Parser {
  mu::Parser parser;
  mutable double t = 0, x = 0, y = 0, z = 0;

  explicit Parser(const std::string& text) {
    parser.DefineVar("t", &t);
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.DefineConst("pi", kPi);
    parser.DefineConst("e", 2.718281828459045235);
    parser.SetExpr(text);
    parser.Eval();  // compiles; reports syntax errors and unknown names now
  }
};

Expression::Expression(const std::string& text, std::string source) : text_(text), source_(std::move(source)) {
  try {
    parser_ = std::make_unique<Parser>(text);
  } catch (const mu::Parser::exception_type& e) {
    throw std::invalid_argument(e.GetMsg());
  }
}

Expression::Expression(Real value) : Expression(fmt::format("{:.17g}", value)) {}

Expression::~Expression() = default;

Expression::Expression(const Expression& other) : Expression(other.text_, other.source_) {}

bool Expression::uses_position() const {
  const auto used = parser_->parser.GetUsedVar();
  return used.count("x") || used.count("y") || used.count("z");
}

Real Expression::operator()(Real t, const Vec3& x) const {
  parser_->t = t;
  parser_->x = x.x();
  parser_->y = x.y();
  parser_->z = x.z();
  const Real value = parser_->parser.Eval();
  if (!std::isfinite(value)) {
    const std::string where = uses_position() ? fmt::format(" and x = ({}, {}, {}) m", x.x(), x.y(), x.z()) : "";
    throw NumericalError(fmt::format("{}{}\"{}\" evaluates to {} at t = {} s{}; a load, prescribed value or initial "
                                     "condition must be finite",
                                     source_, source_.empty() ? "" : ": ", text_, value, t, where));
  }
  return value;
}

}  // namespace moreau
