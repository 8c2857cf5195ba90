#include "tle_fetcher.hpp"

#include <curl/curl.h>

namespace rotord::linux_port {
namespace {

constexpr std::size_t kMaxBytes = 1 << 20;

std::size_t on_data(char* data, std::size_t size, std::size_t count, void* user) {
  auto* text = static_cast<std::string*>(user);
  const std::size_t n = size * count;
  if (text->size() + n > kMaxBytes) return 0;  // aborts the transfer
  text->append(data, n);
  return n;
}

}  // namespace

TleFetcher::TleFetcher(asio::io_context& io) : io_(io) {
  // Before any thread: libcurl's global set-up is not thread-safe.
  curl_global_init(CURL_GLOBAL_DEFAULT);
}

TleFetcher::~TleFetcher() {
  if (thread_.joinable()) thread_.join();
  curl_global_cleanup();
}

bool TleFetcher::fetch(const std::string& url, Done done) {
  if (busy_) return false;
  if (thread_.joinable()) thread_.join();
  busy_ = true;
  thread_ = std::thread([this, url, done = std::move(done)] {
    std::string text;
    std::string why;
    bool ok = false;
    CURL* curl = curl_easy_init();
    if (curl == nullptr) {
      why = "libcurl could not start";
    } else {
      char error[CURL_ERROR_SIZE] = "";
      curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
      curl_easy_setopt(curl, CURLOPT_PROTOCOLS_STR, "http,https");
      curl_easy_setopt(curl, CURLOPT_REDIR_PROTOCOLS_STR, "http,https");
      curl_easy_setopt(curl, CURLOPT_FOLLOWLOCATION, 1L);
      curl_easy_setopt(curl, CURLOPT_MAXREDIRS, 5L);
      curl_easy_setopt(curl, CURLOPT_TIMEOUT, 30L);
      curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
      curl_easy_setopt(curl, CURLOPT_USERAGENT, "rotord/" ROTORD_VERSION);
      curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, &on_data);
      curl_easy_setopt(curl, CURLOPT_WRITEDATA, &text);
      curl_easy_setopt(curl, CURLOPT_ERRORBUFFER, error);
      const CURLcode rc = curl_easy_perform(curl);
      long status = 0;
      curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &status);
      if (rc != CURLE_OK) {
        why = error[0] != '\0' ? error : curl_easy_strerror(rc);
      } else if (status < 200 || status > 299) {
        why = "HTTP status " + std::to_string(status);
      } else {
        ok = true;
      }
      curl_easy_cleanup(curl);
    }
    asio::post(io_, [this, ok, text = ok ? std::move(text) : why, done] {
      busy_ = false;
      done(ok, text);
    });
  });
  return true;
}

}  // namespace rotord::linux_port
