// uses: SCAN
// Sets u_count values of the buffer bound at B_SCAN to u_value.
layout(local_size_x = WG) in;
uniform uint u_count;
uniform uint u_value;
void main()
{
    uint i = gid();
    if (i < u_count) scan_[i] = u_value;
}
