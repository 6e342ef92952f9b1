/* Host-side variables the README snippets refer to (tests/check_readme.sh):
   a [-1,1]^3 cube mesh and one ray with its host hit on that mesh. */
static const double cube_xyz[24] = {-1, -1, -1, 1, -1, -1, 1, 1, -1, -1, 1, -1,
                                    -1, -1, 1,  1, -1, 1,  1, 1, 1,  -1, 1, 1};
static const unsigned cube_tris[36] = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7, 0, 1, 5, 0, 5, 4,
                                       2, 3, 7, 2, 7, 6, 1, 2, 6, 1, 6, 5, 0, 4, 7, 0, 7, 3};
/* a ray toward the edge x = y = 1 at z = 0, hitting face x = +1 (triangle 8) at t = 4 */
static const double o[3] = {5, 0.99, 0}, dir[3] = {-1, 0, 0};
static const unsigned tri = 8;
static const double t = 4.0;
