#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "floorgrid/mapping/point_mapping.hpp"
#include "floorgrid/server/map_request.hpp"
#include "floorgrid/server/request_slots.hpp"
// Last: cpp-httplib's <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen's headers
// after it.
#include <httplib.h>  // NOLINT(llvm-include-order)

namespace floorgrid::server {

/// Answers `body` with `status`. Bytes that are not UTF-8 are replaced, not thrown about: an
/// answer is always written (messages repeat a request's bytes only through printable_text).
void answer_json(httplib::Response& res, const nlohmann::json& body, int status = 200);

/// Answers {"error": message} with `status`.
void answer_error(httplib::Response& res, int status, const std::string& message);

/// Runs `work`, answering a RequestError with its status and message (a 503 with Retry-After:
/// 1) and the library's InputError with 400.
void answering_errors(httplib::Response& res, const std::function<void()>& work);

/// Sends `bytes` from where they are, without a copy per request; `owner` (if any) keeps them
/// alive until they are sent (layers a refit replaces meanwhile).
void answer_bytes(httplib::Response& res, const std::string& bytes, const char* type,
                  std::shared_ptr<const void> owner = nullptr);

/// Answers POST /api/map's `request` by `model`: whole when it has at most `streamed_points`,
/// else in chunks as they are mapped (chunked transfer encoding), so that a million points hold
/// 32 bytes each while they are sent, never their JSON; `slot` (a large request's) is held until
/// the last chunk is sent.
void answer_mapped_points(httplib::Response& res, std::shared_ptr<const PointMapping> model,
                          MapRequest request, std::optional<RequestSlots::Slot> slot,
                          std::size_t streamed_points);

}  // namespace floorgrid::server
