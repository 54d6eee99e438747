// The league's field size (SSL_GeometryFieldSize, millimetres) as the shared vocabulary's FieldGeometry
// (metres), converted once for every reader of SSL-Vision geometry (the simulator's control, sslctl).
#pragma once

#include "libs/domain/field.h"
#include "proto/ssl_vision_geometry.pb.h"

namespace ssl::league {

/// SSL_GeometryFieldSize (millimetres) -> FieldGeometry (metres). Optional fields not sent keep the division's
/// defaults (division B for a field up to 10 m long, else A). Sizes are not checked: a caller that needs
/// positive ones checks them.
FieldGeometry field_from_proto(const SSL_GeometryFieldSize& field);

}  // namespace ssl::league
