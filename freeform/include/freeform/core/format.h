#pragma once
// Numbers in messages: the shortest text that reads back to exactly the same value
// (std::to_chars), so an error shows the problem itself: "1.000000001 is not inside the domain
// (0, 1)" where %f printed "1.000000 ... (0.000000, 1.000000)", and "(0, 1e-08)" where it printed
// "(0.000000, 0.000000)".

#include <charconv>
#include <string>
#include <type_traits>

namespace freeform {

/// `x` as the shortest decimal text that reads back to exactly `x` ("0.1", "1e-08", "inf", "nan").
template <class Scalar>
std::string formatNumber(Scalar x)
{
    static_assert(std::is_floating_point_v<Scalar>, "formatNumber takes float, double or long double");
    char buffer[64];
    const auto result = std::to_chars(buffer, buffer + sizeof buffer, x);
    return std::string(buffer, result.ptr);
}

} // namespace freeform
