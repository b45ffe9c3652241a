// The service served: the transport (net/) with the service as its
// MessageHandler and the service's HTTP routes.
#pragma once

#include <memory>

#include "provider/net/http_routes.hpp"
#include "provider/net/server.hpp"
#include "provider/service/service.hpp"

namespace umf::provider {

// Each handler beside its feature: uploads (PUT /up/...), the share target
// (POST /share), downloads (GET or HEAD /dl/...), the nearby screens and this
// screen's field (/nearby.json, /field.json) and the web client's files.
std::shared_ptr<const HttpRoutes> make_http_routes(std::shared_ptr<const Service> service);

// A server (not yet started) for the service's sessions and routes.
std::unique_ptr<Server> make_server(std::shared_ptr<const Service> service, const TlsIdentity& identity,
                                    ServerOptions options = {});

}  // namespace umf::provider
