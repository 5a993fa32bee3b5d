#include "moreau/math/expression.hpp"

#include <fmt/format.h>
#include <muParser.h>

#include <stdexcept>

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

Expression::Expression(const std::string& text) : text_(text) {
  try {
    parser_ = std::make_unique<Parser>(text);
  } catch (const mu::Parser::exception_type& e) {
    throw std::invalid_argument(e.GetMsg());
  }
}

Expression::Expression(Real value) : Expression(fmt::format("{:.17g}", value)) {}

Expression::~Expression() = default;

Expression::Expression(const Expression& other) : Expression(other.text_) {}

bool Expression::uses_position() const {
  const auto used = parser_->parser.GetUsedVar();
  return used.count("x") || used.count("y") || used.count("z");
}

Real Expression::operator()(Real t, const Vec3& x) const {
  parser_->t = t;
  parser_->x = x.x();
  parser_->y = x.y();
  parser_->z = x.z();
  return parser_->parser.Eval();
}

}  // namespace moreau
