#include "floorgrid/server/http_answers.hpp"

#include <algorithm>
#include <utility>

#include "floorgrid/core/error.hpp"

namespace floorgrid::server {

void answer_json(httplib::Response& res, const nlohmann::json& body, int status) {
  res.status = status;
  res.set_content(body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace),
                  "application/json");
}

void answer_error(httplib::Response& res, int status, const std::string& message) {
  answer_json(res, {{"error", message}}, status);
}

void answering_errors(httplib::Response& res, const std::function<void()>& work) {
  try {
    work();
  } catch (const RequestError& e) {
    if (e.status() == 503)
      res.set_header("Retry-After", "1");
    answer_error(res, e.status(), e.what());
  } catch (const InputError& e) {
    answer_error(res, 400, e.what());  // the library's word on the request's data
  }
}

void answer_bytes(httplib::Response& res, const std::string& bytes, const char* type,
                  std::shared_ptr<const void> owner) {
  res.set_content_provider(
      bytes.size(), type,
      [owner, &bytes](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
        static_cast<void>(owner);  // held, not used
        return sink.write(bytes.data() + offset, std::min<std::size_t>(length, 1u << 16));
      });
}

namespace {

/// What a streamed POST /api/map answer holds while it is sent: the model, the points and the
/// slot of a large request.
struct MappedStream {
  std::shared_ptr<const PointMapping> model;
  MapRequest request;
  std::optional<RequestSlots::Slot> slot;
  std::size_t next = 0;  ///< the first point not sent
};

/// Points mapped and sent per chunk of a streamed answer.
constexpr std::size_t kPointsPerChunk = 4096;

}  // namespace

void answer_mapped_points(httplib::Response& res, std::shared_ptr<const PointMapping> model,
                          MapRequest request, std::optional<RequestSlots::Slot> slot,
                          std::size_t streamed_points) {
  if (request.points.size() <= streamed_points) {
    res.set_content(mapped_points_text(request, *model), "application/json");
    return;
  }
  auto stream = std::make_shared<MappedStream>(
      MappedStream{std::move(model), std::move(request), std::move(slot), 0});
  res.set_chunked_content_provider(
      "application/json", [stream](std::size_t, httplib::DataSink& sink) {
        // An exception here would escape cpp-httplib (it runs while writing): end the answer.
        try {
          MappedStream& s = *stream;
          const std::size_t n = s.request.points.size();
          std::string chunk = s.next == 0 ? mapped_points_head(s.request, *s.model) : "";
          const std::size_t end = std::min(n, s.next + kPointsPerChunk);
          append_mapped_points(chunk, s.request, *s.model, s.next, end);
          s.next = end;
          if (end == n)
            chunk += mapped_points_tail();
          if (!sink.write(chunk.data(), chunk.size()))
            return false;
          if (end == n)
            sink.done();
          return true;
        } catch (...) {
          return false;
        }
      });
}

}  // namespace floorgrid::server
