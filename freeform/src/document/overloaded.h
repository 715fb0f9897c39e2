#pragma once
// Internal to the document layer: the usual overload set for std::visit over a variant of object
// data (document/model.cpp, document/operations.cpp).

namespace freeform::detail {

template <class... F>
struct Overloaded : F... {
    using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

} // namespace freeform::detail
