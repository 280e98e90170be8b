// Module objects own GL objects (through their unique_ptr<Impl>): neither copyable nor
// movable, so that no two objects ever delete the same textures. The headers do not spell
// the deleted operations out; this test holds them to it.
#include "obscura/obscura.hpp"
#include "obscura/headless.hpp"
#include "obscura/reference.hpp"

#include <catch2/catch.hpp>

#include <type_traits>

namespace {
template <class T>
constexpr bool pinned = !std::is_copy_constructible_v<T> && !std::is_copy_assignable_v<T> &&
                        !std::is_move_constructible_v<T> && !std::is_move_assignable_v<T>;
} // namespace

TEST_CASE("module objects are neither copyable nor movable", "[unit]") {
    using namespace obscura;
    STATIC_REQUIRE(pinned<Context>);
    STATIC_REQUIRE(pinned<GBuffer>);
    STATIC_REQUIRE(pinned<AmbientOcclusion>);
    STATIC_REQUIRE(pinned<IndirectLight>);
    STATIC_REQUIRE(pinned<DirectionalOcclusion>);
    STATIC_REQUIRE(pinned<EnvironmentMap>);
    STATIC_REQUIRE(pinned<Composer>);
    STATIC_REQUIRE(pinned<ScreenVisibility>);
    STATIC_REQUIRE(pinned<ShadowMaps>);
    STATIC_REQUIRE(pinned<Voxelizer>);
    STATIC_REQUIRE(pinned<Profiler>);
    STATIC_REQUIRE(pinned<headless::HeadlessContext>);
    STATIC_REQUIRE(pinned<reference::RayScene>);
}
