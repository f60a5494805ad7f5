// src/collect/assets.hpp - the web page's files, embedded at build time (cmake/embed_assets.cmake).
#pragma once

#include <cstddef>
#include <string_view>

namespace feint::collect::detail {

struct Asset {
  std::string_view name;  // file name in src/collect/assets/
  std::string_view data;
};
extern const Asset kAssets[];
extern const std::size_t kAssetCount;

}  // namespace feint::collect::detail
