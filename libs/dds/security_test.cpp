// The security section of the site's dds config, and how Participant::create treats missing or broken
// security files: a clear error, never a crash. (Who may talk to whom: tests/integration/dds_security_test.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "libs/common/deploy_files.h"
#include "libs/dds/discovery.h"
#include "libs/dds/participant.h"

namespace ssl::dds {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

Result<SiteDdsConfig> site_config(const std::string& site) {
  auto layers = config_layers("dds", site, "");
  if (!layers) return layers.error();
  return load_site_dds_config(*layers);
}

TEST(SecurityConfig, OnInTheFieldSiteOffInTheSimulatorSite) {
  ::unsetenv("SSL_CERTS_DIR");
  auto field = site_config("field");
  ASSERT_TRUE(field) << field.error().message;
  EXPECT_TRUE(field->security.enabled);
  EXPECT_EQ(security_directory(field->security), "/etc/ssl-stack/certs");
  auto sim = site_config("sim");
  ASSERT_TRUE(sim) << sim.error().message;
  EXPECT_FALSE(sim->security.enabled);
}

TEST(SecurityConfig, ARelativeDirectoryIsABadConfig) {
  const fs::path dir = fs::temp_directory_path() / ("ssl_security_config_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "dds.yaml") << "security:\n  enabled: true\n  directory: certs\n";
  auto loaded = site_config(dir.string());
  fs::remove_all(dir);
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message, HasSubstr("not an absolute path"));
}

TEST(SecurityConfig, ADiscoveryServerWithSecurityIsABadConfig) {
  const fs::path dir = fs::temp_directory_path() / ("ssl_security_server_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "dds.yaml") << "discovery: server\nservers: [127.0.0.1:11811]\nsecurity:\n  enabled: true\n";
  auto loaded = site_config(dir.string());
  fs::remove_all(dir);
  ASSERT_FALSE(loaded);
  EXPECT_THAT(loaded.error().message, HasSubstr("cannot authenticate"));
}

TEST(SecurityConfig, TheEnvironmentBeatsTheConfiguredDirectory) {
  ::setenv("SSL_CERTS_DIR", "/tmp/elsewhere", 1);
  EXPECT_EQ(security_directory({.enabled = true, .directory = "/etc/ssl-stack/certs"}), "/tmp/elsewhere");
  ::unsetenv("SSL_CERTS_DIR");
  EXPECT_EQ(security_directory({.enabled = true, .directory = "/etc/ssl-stack/certs"}), "/etc/ssl-stack/certs");
}

TEST(SecureParticipant, MissingFilesAreNamedWithHowToMakeThem) {
  ::unsetenv("SSL_CERTS_DIR");
  auto participant = Participant::create(
      {.domain_id = 177, .security = {.enabled = true, .directory = "/nonexistent/certs"}, .identity = "blue"});
  ASSERT_FALSE(participant);
  EXPECT_THAT(participant.error().message, HasSubstr("/nonexistent/certs/ca.pem does not exist"));
  EXPECT_THAT(participant.error().message, HasSubstr("./ssl certs"));
}

TEST(SecureParticipant, ABrokenCertificateIsAnErrorNotACrash) {
  ::unsetenv("SSL_CERTS_DIR");
  const fs::path dir = fs::temp_directory_path() / ("ssl_security_broken_" + std::to_string(::getpid()));
  auto script = find_deploy_file("dds-certs.sh");
  ASSERT_TRUE(script) << script.error().message;
  ASSERT_EQ(std::system(("'" + *script + "' --dir '" + dir.string() + "' --teams blue >/dev/null").c_str()), 0);
  const SecurityConfig security{.enabled = true, .directory = dir.string()};
  // The files as made are good...
  EXPECT_TRUE(Participant::create({.domain_id = 177, .security = security, .identity = "blue"}));
  // ...an identity the directory does not have is named...
  auto unknown = Participant::create({.domain_id = 177, .security = security, .identity = "yellow"});
  ASSERT_FALSE(unknown);
  EXPECT_THAT(unknown.error().message, HasSubstr("yellow/cert.pem does not exist"));
  // ...and a certificate that is not one fails creation with a message.
  std::ofstream(dir / "blue" / "cert.pem") << "not a certificate\n";
  auto broken = Participant::create({.domain_id = 177, .security = security, .identity = "blue"});
  fs::remove_all(dir);
  ASSERT_FALSE(broken);
  EXPECT_THAT(broken.error().message, HasSubstr("cannot create a secure DDS participant"));
}

}  // namespace
}  // namespace ssl::dds
