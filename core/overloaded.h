// std::visit over a variant with one lambda per alternative (the C++17 idiom):
//   std::visit(Overloaded{[](A a) {...}, [](B b) {...}}, variant);
#pragma once

namespace rtbench {

template <class... Fs>
struct Overloaded : Fs... {
    using Fs::operator()...;
};
template <class... Fs>
Overloaded(Fs...) -> Overloaded<Fs...>;

}  // namespace rtbench
