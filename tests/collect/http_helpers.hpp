// Helpers of the feint collect tests that speak HTTP: one request on a new connection, and the
// body of a round.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <string>
#include <vector>

#include "feint/collect/study.hpp"
#include "feint/io/number.hpp"

namespace feint::collect::testing {

struct HttpReply {
  int status = 0;
  std::string body;
};

/// One request to 127.0.0.1:`port` on a new connection (closed after the answer).
inline HttpReply request(unsigned short port, boost::beast::http::verb method,
                         const std::string& target, const std::string& body = "") {
  namespace http = boost::beast::http;
  using tcp = boost::asio::ip::tcp;
  boost::asio::io_context ioc;
  tcp::socket sock(ioc);
  sock.connect(tcp::endpoint(boost::asio::ip::make_address("127.0.0.1"), port));
  http::request<http::string_body> req(method, target, 11);
  req.set(http::field::host, "127.0.0.1");
  req.keep_alive(false);
  req.body() = body;
  req.prepare_payload();
  http::write(sock, req);
  boost::beast::flat_buffer buf;
  http::response<http::string_body> res;
  http::read(sock, buf, res);
  return {static_cast<int>(res.result_int()), res.body()};
}

/// A trace as the page sends it: "t,pad" lines.
inline std::string trace_body(const std::vector<PadSample>& s) {
  std::string b;
  for (const auto& x : s) b += io::format_double(x.t) + "," + io::format_double(x.pad) + "\n";
  return b;
}

}  // namespace feint::collect::testing
