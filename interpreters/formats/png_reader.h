#pragma once
// PNG input through libpng's simplified API: any PNG it reads, as 8-bit RGB (what a
// sweep's contact sheet puts its thumbnails together from).

#include <filesystem>
#include <optional>

#include "interpreters/formats/renderer.h"

namespace ontogen {

/// The picture in `path` as 8-bit RGB (alpha composed over black by libpng), or nothing
/// when the file is missing or no PNG libpng reads.
std::optional<Image> readPng(const std::filesystem::path& path);

}  // namespace ontogen
