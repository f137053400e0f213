/* tlod bench --peers in a tlod built without OpenSubdiv: what is missing and
 * how to get it (the suite is optional, its absence never a silent skip). */
#include "bench_peers.h"
#include "cli.h"

int bench_peers(const bench_options* o, json_writer* json, FILE* csv) {
  (void)o, (void)json, (void)csv;
  return cli_error(CLI_FAILED, "bench --peers: this tlod was built without OpenSubdiv (TLOD_WITH_OPENSUBDIV): "
                               "install it with 'sudo scripts/bootstrap --peers' (Debian 12: apt-get install "
                               "libosd-dev), configure again (cmake --preset release) and rebuild");
}
