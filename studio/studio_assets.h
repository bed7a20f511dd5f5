#pragma once
// The studio's web page, built into the executable: index.html, the stylesheet and the
// script bundled with three.js at build time (studio/web/, bundled by esbuild from
// the npm packages .ci/setup fetches). Nothing is fetched from the internet at run time.

#include <span>
#include <string_view>

namespace ontogen::studio {

struct StudioAsset {
  std::string_view path;         ///< as the page asks for it: "/", "/studio.js"
  std::string_view contentType;
  std::string_view bytes;
};

/// The page's files; empty when the build had no bundler (the studio then says so).
std::span<const StudioAsset> studioAssets();

}  // namespace ontogen::studio
