#include "libs/service/setup.h"

#include "libs/common/deploy_files.h"

namespace ssl::service {

Result<Setup> prepare(std::string_view service, const std::string& site_flag, const std::string& config_file,
                      std::string_view instance) {
  Setup setup;
  setup.site = chosen_site(site_flag);
  if (!instance.empty()) setup.saved_parameters = saved_parameters_file(instance);
  if (!service.empty()) {
    auto layers = config_layers(service, setup.site, config_file, setup.saved_parameters);
    if (!layers) return layers.error();
    setup.config_files = std::move(*layers);
  }
  auto dds_layers = config_layers("dds", setup.site, "");
  if (!dds_layers) return dds_layers.error();
  auto dds = dds::load_site_dds_config(*dds_layers);
  if (!dds) return dds.error();
  setup.discovery = std::move(dds->discovery);
  setup.security = std::move(dds->security);
  return setup;
}

std::string describe(const Setup& setup, std::string_view identity) {
  std::string text = setup.site.empty() ? "no site" : "site " + setup.site;
  if (!setup.config_files.empty()) {
    text += ", config";
    for (std::size_t i = 0; i < setup.config_files.size(); ++i) {
      text += (i == 0 ? " " : " + ") + setup.config_files[i];
    }
  }
  return text + ", discovery " + dds::describe(setup.discovery) + ", DDS security " +
         dds::describe(setup.security, identity);
}

}  // namespace ssl::service
