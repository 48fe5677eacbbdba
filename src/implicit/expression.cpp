// F from a text expression, with muparser (Debian libmuparser-dev 2.3.3).
// The implicit module owns this so that the library (and the Python
// bindings) take the same expressions as the command line.
#include <algorithm>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <muParser.h>

#include "polyvol/implicit.hpp"

namespace polyvol {

namespace {

// 1-based coordinate named by a variable (x, y, z, x1 .. x99), or 0.
int coordinate_of(const std::string& name) {
    if (name == "x") return 1;
    if (name == "y") return 2;
    if (name == "z") return 3;
    if (name.size() >= 2 && name.size() <= 3 && name[0] == 'x' && name[1] != '0') {
        int k = 0;
        for (std::size_t i = 1; i < name.size(); ++i) {
            if (name[i] < '0' || name[i] > '9') return 0;
            k = 10 * k + (name[i] - '0');
        }
        return k;
    }
    return 0;
}

ExpressionError to_error(const mu::Parser::exception_type& e) {
    return ExpressionError("bad expression: " + e.GetMsg(), e.GetPos());
}

struct State {
    mu::Parser parser;
    std::vector<double> x;
};

// The parser with every name the expression uses known; throws for a syntax
// error or a name that is not a coordinate within `dimension` (or any, when
// dimension is 0), returning the highest coordinate used.
int check_names(mu::Parser& parser, const std::string& expression, int dimension) {
    int highest = 0;
    try {
        parser.DefineConst("pi", 3.14159265358979323846);
        parser.SetExpr(expression);
        for (const auto& [name, pointer] : parser.GetUsedVar()) {
            const int k = coordinate_of(name);
            if (k == 0) throw ExpressionError("bad expression: unknown name \"" + name + "\"", -1);
            if (dimension > 0 && k > dimension)
                throw ExpressionError("bad expression: \"" + name + "\" is not a coordinate in " +
                                          std::to_string(dimension) + " dimensions",
                                      -1);
            highest = std::max(highest, k);
        }
    } catch (const mu::Parser::exception_type& e) {
        throw to_error(e);
    }
    return highest;
}

}  // namespace

int expression_coordinates(const std::string& expression) {
    mu::Parser parser;
    return check_names(parser, expression, 0);
}

ImplicitFunction parse_implicit_expression(const std::string& expression, int dimension) {
    if (dimension < 1 || dimension > 99) throw std::invalid_argument("expression: dimension out of range");
    auto state = std::make_shared<State>();
    state->x.assign(static_cast<std::size_t>(dimension), 0.0);
    check_names(state->parser, expression, dimension);
    try {
        const char* axes[] = {"x", "y", "z"};
        for (int k = 0; k < dimension; ++k) {
            if (k < 3) state->parser.DefineVar(axes[k], &state->x[k]);
            std::string name = "x";
            name += std::to_string(k + 1);
            state->parser.DefineVar(name, &state->x[k]);
        }
        state->parser.SetExpr(expression);
        static_cast<void>(state->parser.Eval());  // parses fully: every error shows now
    } catch (const mu::Parser::exception_type& e) {
        throw to_error(e);
    }
    return [state](std::span<const double> p) {
        std::copy(p.begin(), p.end(), state->x.begin());
        try {
            return state->parser.Eval();
        } catch (const mu::Parser::exception_type&) {
            return std::numeric_limits<double>::quiet_NaN();  // reported as F = NaN at this point
        }
    };
}

}  // namespace polyvol
