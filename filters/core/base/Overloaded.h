#pragma once
// One visitor from several lambdas, for std::visit over a variant: each alternative is handled
// by the lambda that takes it, and an alternative no lambda takes fails to compile there.
namespace shadelab
{
template<typename... Handlers>
struct Overloaded : Handlers...
{
  using Handlers::operator()...;
};
template<typename... Handlers>
Overloaded(Handlers...) -> Overloaded<Handlers...>;
}
