// The operator screen's page, embedded at build time from firmware/hubctl/web/ (embed_web.cmake):
// no file to install, nothing fetched from elsewhere.
#pragma once

#include <string_view>

namespace hubrt::hubctl::web {

extern const std::string_view kIndexHtml;
extern const std::string_view kScreenJs;
extern const std::string_view kScreenCss;

}  // namespace hubrt::hubctl::web
